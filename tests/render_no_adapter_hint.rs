//! Without a usable adapter, `GpuContext::new` fails with one line that says what to install
//! (docs/design.md, Tests). The test re-runs itself in a child process whose Vulkan loader is pointed
//! at a driver manifest that does not exist, so no adapter can be found there.

use std::process::Command;

use wingman::render::GpuContext;
use wingman::render::gpu::INSTALL_HINT;

const TEST_NAME: &str = "render_no_adapter_hint::missing_driver_error_names_the_install_command";
const CHILD_FLAG: &str = "WINGMAN_TEST_NO_ADAPTER_CHILD";

#[test]
fn missing_driver_error_names_the_install_command() {
    if std::env::var_os(CHILD_FLAG).is_some() {
        let message = match GpuContext::new() {
            Ok(gpu) => panic!("found an adapter without drivers: {}", gpu.description()),
            Err(e) => e.to_string(),
        };
        assert!(message.contains(INSTALL_HINT), "{message}");
        assert!(!message.contains('\n'), "{message}");
        return;
    }
    let exe = std::env::current_exe().expect("test executable path");
    let missing = "/nonexistent/wingman_no_such_icd.json";
    let output = Command::new(exe)
        .args([TEST_NAME, "--exact", "--nocapture", "--test-threads", "1"])
        .env(CHILD_FLAG, "1")
        .env("VK_ICD_FILENAMES", missing)
        .env("VK_DRIVER_FILES", missing)
        .output()
        .expect("child test runs");
    assert!(
        output.status.success(),
        "child failed:\n{}\n{}",
        String::from_utf8_lossy(&output.stdout),
        String::from_utf8_lossy(&output.stderr)
    );
    // The child really ran the test (and did not filter it away).
    assert!(String::from_utf8_lossy(&output.stdout).contains("1 passed"));
}
