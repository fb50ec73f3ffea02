# The image the cluster files run (studies/cluster/, docs/studies.md, On a cluster): the
# repository in /repo with `target/release/wingman` built (also on the PATH as `wingman`) and
# the system packages of scripts/packages.txt installed by scripts/setup.sh, the same list a
# workstation and CI install.
#
#   docker build --tag wingman:latest .
#   docker run --rm -v "$PWD/runs:/repo/runs" wingman:latest \
#       wingman sweep studies/monte_carlo.toml --jobs 4
FROM rust:1-bookworm AS build
WORKDIR /repo
COPY . .
RUN cargo build --release --locked --bin wingman

FROM debian:bookworm-slim
WORKDIR /repo
COPY scripts/setup.sh scripts/packages.txt scripts/
RUN sh scripts/setup.sh && rm -rf /var/lib/apt/lists/*
COPY . .
COPY --from=build /repo/target/release/wingman target/release/wingman
RUN ln -s /repo/target/release/wingman /usr/local/bin/wingman
# Quiets Mesa's device selection layer (docs/design.md, The camera on a CPU).
ENV NODEVICE_SELECT=1
CMD ["wingman", "--help"]
