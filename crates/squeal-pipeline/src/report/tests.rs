use super::*;

/// The files section links every file under the folder, its sub-folders included, and
/// leaves out the report's own files and hidden ones.
#[test]
fn the_files_section_links_every_file() {
    let dir = std::env::temp_dir().join(format!("squeal-files-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    for f in [
        "a.csv",
        "chbm/cycle/x 1.vtu",
        "index.html",
        "table-1.csv",
        ".hidden",
    ] {
        let p = dir.join(f);
        std::fs::create_dir_all(p.parent().unwrap()).unwrap();
        std::fs::write(&p, b"").unwrap();
    }
    let s = files_section(&dir);
    assert!(s.text.contains("[a.csv](a.csv)"), "{}", s.text);
    assert!(
        s.text.contains("[x 1.vtu](chbm/cycle/x%201.vtu)"),
        "{}",
        s.text
    );
    for absent in ["index.html", "table-1.csv", ".hidden"] {
        assert!(!s.text.contains(absent), "{absent}: {}", s.text);
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The comparison section holds each level's Table 1 and 2 with the level in the caption,
/// the overlays, every failure in full and the level's files as links; without a
/// comparison it says it was not run.
#[test]
fn the_comparison_section_shows_tables_overlays_and_failures() {
    let mut t1 = Table::new(["", "CHBM 3H"]);
    t1.push_row(["displacement error, all dofs (%)", "1.32"]);
    let mut t2 = Table::new(["method", "outcome"]);
    t2.push_row(["BDF 1e-5", "failed: no steady oscillation by t = 1.2296 s"]);
    let c = CompareSummary {
        levels: vec![crate::compare::CompareLevel {
            ratio: 1.1,
            mu: 0.508005,
            folder: "mu_1.100".into(),
            table1: t1.clone(),
            table2: t2.clone(),
            failures: vec![
                "BDF time integration at rtol 1e-5: no steady oscillation by t = 1.2296 s: \
                 4848 cycles seen"
                    .into(),
            ],
            files: vec!["table1.csv".into(), "limit_cycles.svg".into()],
        }],
        error_definition: "RMS of the difference",
        json: serde_json::Value::Null,
    };
    let s = compare_section(Some(&c));
    assert_eq!(s.heading, "CHBM against time integration");
    assert!(
        s.text.contains("Errors: RMS of the difference."),
        "{}",
        s.text
    );
    assert_eq!(
        s.figures[0].0,
        PathBuf::from("compare/mu_1.100/limit_cycles")
    );
    assert!(s.figures[0].1.contains("over the reference limit cycle"));
    assert_eq!(s.tables.len(), 2);
    assert_eq!(s.tables[0].0, t1);
    assert!(
        s.tables[0].1.contains("At 1.100 μ0 (μ = 0.508005)")
            && s.tables[0].1.contains("the paper's Table 1"),
        "{}",
        s.tables[0].1
    );
    assert!(s.tables[1].1.contains("the paper's Table 2"));
    assert!(
        s.after.contains("What did not converge at 1.100 μ0:\n\n- BDF time integration at rtol 1e-5: no steady oscillation by t = 1.2296 s: 4848 cycles seen\n"),
        "{}",
        s.after
    );
    assert!(
        s.after
            .contains("[table1.csv](compare/mu_1.100/table1.csv), [limit_cycles.svg](compare/mu_1.100/limit_cycles.svg)"),
        "{}",
        s.after
    );
    let none = compare_section(None);
    assert!(none.text.starts_with("Not run (`squeal run --no-compare`)"));
    assert!(none.tables.is_empty() && none.figures.is_empty());
}
