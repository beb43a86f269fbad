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

/// A path that is no regular file (an endless device, a FIFO, a folder) is refused before
/// any byte is read, and so is a file above the size bound (a sparse file: its length is
/// known without writing it), each naming the path and what to give instead (issue 22).
#[cfg(unix)]
#[test]
fn endless_streams_and_huge_files_are_refused() {
    let dir = std::env::temp_dir().join(format!("squeal-mesh-streams-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let fifo = dir.join("stream.inp");
    let made = std::process::Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .unwrap();
    assert!(made.success());
    let folder = dir.join("folder.msh");
    std::fs::create_dir_all(&folder).unwrap();
    // /dev/zero has no mesh extension: ask each reader directly.
    let zero = Path::new("/dev/zero");
    for (what, err) in [
        ("/dev/zero", squeal_mesh::inp::read(zero).unwrap_err()),
        ("/dev/zero", squeal_mesh::msh::read(zero).unwrap_err()),
        ("stream.inp", squeal_mesh::read(&fifo).unwrap_err()),
        ("folder.msh", squeal_mesh::read(&folder).unwrap_err()),
    ] {
        let shown = err.to_string();
        assert!(shown.contains(what), "{shown}");
        assert!(shown.contains("not a regular file"), "{shown}");
    }
    let huge = dir.join("huge.inp");
    let f = std::fs::File::create(&huge).unwrap();
    f.set_len(squeal_mesh::file::MAX_FILE_BYTES + 1).unwrap();
    let shown = squeal_mesh::read(&huge).unwrap_err().to_string();
    assert!(
        shown.contains("huge.inp") && shown.contains("above the 4 GiB"),
        "{shown}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
