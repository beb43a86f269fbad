//! The report's list of files: this run's outputs by folder, with their links.

use super::*;

/// Whether `rel` (a `/`-separated path in the output folder) is a file of the report itself:
/// `index.html`, `index.md`, the tables' `table-N.csv` and the pictures in `report/`.
pub fn is_report_file(rel: &str) -> bool {
    rel == "index.html"
        || rel == "index.md"
        || (rel.starts_with("table-") && rel.ends_with(".csv") && !rel.contains('/'))
        || rel.starts_with(&format!("{PICTURES}/"))
}

/// Links to `files`, grouped by folder, one Markdown list item per folder.
pub(super) fn links_by_folder(mut files: Vec<String>, label: impl Fn(&str) -> String) -> String {
    // By folder, then name: a sub-folder's files must not split its parent's list.
    files.sort_by_key(|f| {
        let p = Path::new(f);
        (
            p.parent().map(Path::to_path_buf),
            p.file_name().map(|n| n.to_os_string()),
        )
    });
    let mut by_folder: Vec<(String, Vec<String>)> = Vec::new();
    for f in files {
        let folder = Path::new(&f)
            .parent()
            .map(|p| p.display().to_string())
            .unwrap_or_default();
        match by_folder.last_mut() {
            Some((d, v)) if *d == folder => v.push(f),
            _ => by_folder.push((folder, vec![f])),
        }
    }
    let mut text = String::new();
    for (folder, files) in by_folder {
        let links: Vec<String> = files
            .iter()
            .map(|f| {
                let name = Path::new(f)
                    .file_name()
                    .map(|n| n.to_string_lossy().into_owned())
                    .unwrap_or_default();
                format!("[{name}]({}){}", url_path(f), label(f))
            })
            .collect();
        let label = if folder.is_empty() {
            "this folder".to_string()
        } else {
            format!("`{folder}/`")
        };
        text.push_str(&format!("- {label}: {}\n", links.join(", ")));
    }
    text
}

/// Every file of the output folder, as links grouped by folder (the report's own files
/// excepted: they are this page, its Markdown twin and the tables' CSV files linked from their
/// captions). The files an earlier run wrote and this run did not (the output folder's
/// manifest, [`squeal_io::folder`]) are listed apart, with their run: they are not this run's
/// results.
pub(super) fn files_section(out: &Path) -> Section {
    let mut files = Vec::new();
    list_files(out, Path::new(""), &mut files);
    let earlier = squeal_io::folder::earlier_files(out);
    let is_earlier = |f: &String| earlier.iter().any(|e| e.path == url_like(f));
    let (old, own): (Vec<String>, Vec<String>) = files.into_iter().partition(is_earlier);
    let mut text = format!(
        "Every file of this run, relative to this page (CSV opens in a spreadsheet, SVG and \
         PNG in a browser, `.vtm`, `.vtu` and `.pvd` in ParaView, `.rom` with \
         `tools/rom/read_rom.py`):\n\n{}",
        links_by_folder(own, |_| String::new())
    );
    if !old.is_empty() {
        let run_of = |f: &str| {
            earlier
                .iter()
                .find(|e| e.path == url_like(f))
                .map_or(String::new(), |e| {
                    format!(" (run {}, {})", e.run, e.written)
                })
        };
        text.push_str(&format!(
            "\n**Not from this run:** these files were written by earlier runs into this folder \
             and not rewritten by this one, so they may describe another scene or other \
             settings (`{}` says which run wrote each):\n\n{}",
            squeal_io::folder::MANIFEST,
            links_by_folder(old, run_of)
        ));
    }
    Section {
        heading: "Files".into(),
        text,
        ..Section::default()
    }
}

/// A relative path with `/` separators, as the manifest keeps it.
pub(super) fn url_like(p: &str) -> String {
    p.replace('\\', "/")
}

/// A relative path with `/` separators and unsafe bytes percent-encoded.
pub(super) fn url_path(p: &str) -> String {
    let mut out = String::new();
    for b in p.replace('\\', "/").bytes() {
        if b.is_ascii_alphanumeric() || b"-_.~/".contains(&b) {
            out.push(b as char);
        } else {
            out.push_str(&format!("%{b:02X}"));
        }
    }
    out
}

pub(super) fn list_files(root: &Path, rel: &Path, out: &mut Vec<String>) {
    let Ok(entries) = std::fs::read_dir(root.join(rel)) else {
        return;
    };
    for e in entries.flatten() {
        let name = e.file_name().to_string_lossy().into_owned();
        if name.starts_with('.') {
            continue;
        }
        let path = rel.join(&name);
        match e.file_type() {
            Ok(t) if t.is_dir() => list_files(root, &path, out),
            Ok(t) if t.is_file() => {
                let own = rel.as_os_str().is_empty() && is_report_file(&name);
                if !own {
                    out.push(path.display().to_string());
                }
            }
            _ => {}
        }
    }
}
