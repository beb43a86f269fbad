//! How reader errors read in an error chain: the CLI prints `{:#}` (anyhow), which appends
//! each error's `source()` to its message, so a message must not repeat its source's text.

use std::path::Path;

/// Reading a file that does not exist names the file and gives the operating system's reason
/// once, for both readers.
#[test]
fn a_missing_file_is_reported_once() {
    let dir = std::env::temp_dir().join(format!("squeal-mesh-messages-{}", std::process::id()));
    for name in ["absent.inp", "absent.msh"] {
        let path = dir.join(name);
        let os = std::fs::read(&path).unwrap_err().to_string();
        let err = squeal_mesh::read(&path).unwrap_err();
        for shown in [err.to_string(), format!("{:#}", anyhow::Error::from(err))] {
            assert_eq!(shown.matches(&os).count(), 1, "{shown}");
            assert!(shown.contains(name), "{shown}");
        }
    }
    assert!(!Path::new(&dir).exists());
}
