//! Checks on an output path before anything is computed: it must not be one of the command's
//! inputs (a typo such as `squeal mesh convert pad.inp pad.inp` must not destroy the mesh), and
//! its extension must say what is written into it.

use std::path::{Path, PathBuf};

/// Why an output path is refused.
#[derive(Debug, thiserror::Error, PartialEq, Eq)]
pub enum OutputError {
    /// The output is (or would replace) an input file.
    #[error(
        "{}: this is the {what} this command reads; refusing to write over it (choose another output path)",
        output.display()
    )]
    IsInput { output: PathBuf, what: String },
    /// The output's extension does not match what is written.
    #[error(
        "{}: this command writes {format}, so the output must end in .{expected}",
        output.display()
    )]
    Extension {
        output: PathBuf,
        expected: String,
        format: String,
    },
    /// A folder was expected, and the path is an existing file or looks like a file name.
    #[error(
        "{}: the output of this command is a folder, and this {reason}; give a folder path",
        output.display()
    )]
    NotAFolder { output: PathBuf, reason: String },
}

/// The file's identity: (device, inode) where the platform has them, else its canonical path.
fn identity(p: &Path) -> Option<(u64, u64, PathBuf)> {
    let meta = std::fs::metadata(p).ok()?;
    let canon = std::fs::canonicalize(p).ok()?;
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        Some((meta.dev(), meta.ino(), canon))
    }
    #[cfg(not(unix))]
    {
        let _ = meta;
        Some((0, 0, canon))
    }
}

/// Whether `a` and `b` name the same file: the same path, the same canonical path, or (Unix)
/// the same device and inode (a hard link). Paths that do not exist compare by their text
/// after joining a canonical parent folder.
pub fn same_file(a: &Path, b: &Path) -> bool {
    if a == b {
        return true;
    }
    match (identity(a), identity(b)) {
        (Some((da, ia, ca)), Some((db, ib, cb))) => {
            ca == cb || (cfg!(unix) && da == db && ia == ib)
        }
        _ => {
            let canon_parent = |p: &Path| -> Option<PathBuf> {
                let parent = match p.parent() {
                    Some(d) if !d.as_os_str().is_empty() => d,
                    _ => Path::new("."),
                };
                Some(std::fs::canonicalize(parent).ok()?.join(p.file_name()?))
            };
            matches!((canon_parent(a), canon_parent(b)), (Some(x), Some(y)) if x == y)
        }
    }
}

/// Refuses `output` when it is one of `inputs` (each with what it is, e.g. "pad mesh").
pub fn refuse_inputs(output: &Path, inputs: &[(&Path, &str)]) -> Result<(), OutputError> {
    for (input, what) in inputs {
        if same_file(output, input) {
            return Err(OutputError::IsInput {
                output: output.to_path_buf(),
                what: (*what).to_string(),
            });
        }
    }
    Ok(())
}

/// Refuses `output` unless its extension is `expected` (ASCII case ignored); `format` says
/// what is written (e.g. "VTK XML unstructured grid").
pub fn require_extension(output: &Path, expected: &str, format: &str) -> Result<(), OutputError> {
    let ok = output
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case(expected));
    if ok {
        Ok(())
    } else {
        Err(OutputError::Extension {
            output: output.to_path_buf(),
            expected: expected.to_string(),
            format: format.to_string(),
        })
    }
}

/// Refuses an output folder that is an existing file or whose last component has a file
/// extension of letters (`out.txt`), which would otherwise be created as a folder.
pub fn require_folder(output: &Path) -> Result<(), OutputError> {
    if output.is_file() {
        return Err(OutputError::NotAFolder {
            output: output.to_path_buf(),
            reason: "is an existing file".into(),
        });
    }
    let looks_like_file = !output.is_dir()
        && output
            .extension()
            .and_then(|e| e.to_str())
            .is_some_and(|e| !e.is_empty() && e.chars().all(|c| c.is_ascii_alphabetic()));
    if looks_like_file {
        return Err(OutputError::NotAFolder {
            output: output.to_path_buf(),
            reason: "looks like a file name (it has an extension)".into(),
        });
    }
    Ok(())
}

/// Checks before any work that files can be created in the folder `dir` (made if missing):
/// creates and removes a probe file there. An unwritable output folder is then reported at
/// once, not after minutes of computation.
pub fn check_writable(dir: &Path) -> Result<(), crate::IoError> {
    let probe = dir.join(format!(".squeal-probe-{}", std::process::id()));
    let wrap = |error| crate::IoError::Write {
        path: dir.to_path_buf(),
        error,
    };
    std::fs::create_dir_all(dir).map_err(wrap)?;
    std::fs::File::create(&probe).map_err(wrap)?;
    let _ = std::fs::remove_file(&probe);
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(test: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("squeal-guard-{test}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn an_input_is_recognised_by_path_canonical_path_and_hard_link() {
        let dir = scratch("same");
        let a = dir.join("pad.inp");
        std::fs::write(&a, b"mesh").unwrap();
        // The same file spelt differently: through "sub/.." and through a hard link.
        std::fs::create_dir_all(dir.join("sub")).unwrap();
        let detour = dir.join("sub").join("..").join("pad.inp");
        let link = dir.join("link.inp");
        std::fs::hard_link(&a, &link).unwrap();
        for other in [&a, &detour, &link] {
            let e = refuse_inputs(other, &[(&a, "pad mesh")]).unwrap_err();
            assert!(e.to_string().contains("pad mesh"), "{e}");
        }
        // Another file, and a file that does not exist yet, are allowed.
        std::fs::write(dir.join("disc.inp"), b"other").unwrap();
        assert!(refuse_inputs(&dir.join("disc.inp"), &[(&a, "pad mesh")]).is_ok());
        assert!(refuse_inputs(&dir.join("new.vtu"), &[(&a, "pad mesh")]).is_ok());
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn extensions_and_folders_are_checked() {
        assert!(require_extension(Path::new("a/b.VTU"), "vtu", "VTU").is_ok());
        for bad in ["y.vtk", "y", "y.vtu.bak"] {
            assert!(
                require_extension(Path::new(bad), "vtu", "VTU").is_err(),
                "{bad}"
            );
        }
        let dir = scratch("folder");
        std::fs::write(dir.join("file.txt"), b"").unwrap();
        assert!(require_folder(&dir.join("file.txt")).is_err());
        assert!(require_folder(&dir.join("new.txt")).is_err());
        assert!(require_folder(&dir.join("results")).is_ok());
        assert!(require_folder(&dir).is_ok());
        // A version-like suffix is a folder name, not an extension.
        assert!(require_folder(&dir.join("run.2")).is_ok());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
