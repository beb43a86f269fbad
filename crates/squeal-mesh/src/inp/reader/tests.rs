use super::*;

#[test]
fn element_types() {
    for t in ["C3D10", "C3D10M", "C3D10H", "C3D10HS", "C3D10I", "C3D10MH"] {
        assert!(is_tet10(t), "{t}");
    }
    for t in ["C3D4", "C3D20", "DC3D10", "C3D100", "S8"] {
        assert!(!is_tet10(t), "{t}");
    }
    assert_eq!(other_node_count("S8R"), Some(8));
    assert_eq!(other_node_count("S4R5"), Some(4));
    assert_eq!(other_node_count("C3D20R"), Some(20));
    assert_eq!(other_node_count("C3D8I"), Some(8));
    assert_eq!(other_node_count("SPRINGA"), None);
    assert_eq!(other_node_count("S80"), None);
}

#[test]
fn node_lines() {
    assert_eq!(node_line("7, 1., 2.").unwrap(), (7, [1.0, 2.0, 0.0]));
    assert_eq!(node_line("7, 1., , 3,").unwrap(), (7, [1.0, 0.0, 3.0]));
    assert_eq!(
        node_line("7, 1, 2, 3, 0, 0, 1").unwrap(),
        (7, [1.0, 2.0, 3.0])
    );
    assert!(node_line("7").is_err());
    assert!(node_line("7, 1, 2, 3, 0, 0, 1, 9").is_err());
    assert!(node_line("x, 1, 2").is_err());
    assert!(node_line("7, 1, two").is_err());
}
