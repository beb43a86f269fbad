use super::*;
use safetensors::tensor::SafeTensors;

fn sample() -> ReducedModel {
    let n = 3;
    let info = PartInfo {
        name: "pad".into(),
        role_field: Some(PartRole::Pad),
        mesh: MeshInfo {
            path: "meshes/pad.inp".into(),
            sha256: "00".into(),
            nodes: 10,
            elements: 1,
        },
        interface: InterfaceKind::Patch,
        materials: vec![],
        restraints: vec![RestraintInfo {
            node_set: "ABUTMENT".into(),
            directions: [true, true, false],
            nodes: 4,
        }],
        points: vec![InterfacePoint {
            role: PointRole::Contact,
            node_id: None,
            patch: Some(1),
            position: [0.1, 0.2, 0.3],
            area: Some(1e-4),
            normal: Some([0.0, 0.0, -1.0]),
            surface: None,
            projected: None,
            combines: None,
        }],
        dofs: vec![
            DofLabel::Point {
                point: 0,
                direction: 0,
            },
            DofLabel::Point {
                point: 0,
                direction: 2,
            },
            DofLabel::Mode { mode: 0 },
        ],
        fixed_interface_hz: vec![1234.5],
        full_dofs: 4,
        has_basis: true,
        build: None,
    };
    let k = Mat::from_fn(n, n, |i, j| (i * 10 + j) as f64 + 0.1);
    let m = Mat::from_fn(
        n,
        n,
        |i, j| if i == j { 1.0 } else { 1e-3 * (i + j) as f64 },
    );
    let basis = Basis {
        dof_node: vec![7, 7, 7, 9],
        dof_dir: vec![0, 1, 2, 0],
        values: Mat::from_fn(4, n, |i, j| (i as f64) - 0.5 * j as f64),
    };
    ReducedModel {
        tool_version: "test".into(),
        parts: vec![ReducedPart {
            info,
            k,
            m,
            basis: Some(basis),
        }],
        connections: Vec::new(),
        ties: Vec::new(),
    }
}

/// The file as `safetensors::serialize` writes it from the arrays' bytes (how `to_bytes`
/// made it before the arrays were streamed).
fn safetensors_bytes(model: &ReducedModel) -> Vec<u8> {
    use safetensors::tensor::TensorView;
    let (header, arrays) = model.layout().unwrap();
    let n = u64::from_le_bytes(header[..8].try_into().unwrap()) as usize;
    let json: serde_json::Value = serde_json::from_slice(&header[8..8 + n]).unwrap();
    let meta: HashMap<String, String> =
        serde_json::from_value(json["__metadata__"].clone()).unwrap();
    let owned: Vec<(String, Dtype, Vec<usize>, Vec<u8>)> = arrays
        .iter()
        .map(|(name, a)| {
            let mut bytes = Vec::new();
            a.write(&mut bytes).unwrap();
            (name.clone(), a.dtype(), a.shape(), bytes)
        })
        .collect();
    // Given in the parts' order, not the file's: serialize sorts them itself.
    let views: Vec<(String, TensorView)> = owned
        .iter()
        .rev()
        .map(|(n, d, s, b)| (n.clone(), TensorView::new(*d, s.clone(), b).unwrap()))
        .collect();
    safetensors::serialize(views, Some(meta)).unwrap()
}

#[test]
fn streamed_file_is_what_safetensors_writes() {
    // Two parts, one without a basis: arrays of three types and names out of order.
    let mut model = sample();
    let mut disc = model.parts[0].clone();
    disc.info.name = "disc".into();
    disc.basis = None;
    disc.info.has_basis = false;
    model.parts.insert(0, disc);
    let bytes = model.to_bytes().unwrap();
    assert_eq!(bytes, safetensors_bytes(&model));
    let dir = std::env::temp_dir().join(format!("squeal-rom-stream-{}", std::process::id()));
    let path = dir.join("m.rom");
    model.write(&path).unwrap();
    assert_eq!(std::fs::read(&path).unwrap(), bytes);
    std::fs::remove_dir_all(&dir).ok();
    assert_eq!(ReducedModel::from_bytes(&bytes, &path).unwrap(), model);
}

/// Issue 22: one flipped bit in the arrays, or a NaN written with a matching checksum,
/// is refused as a damaged file naming it; a file without a checksum (written before
/// it was added) still reads.
#[test]
fn damaged_arrays_are_refused_and_files_without_a_checksum_read() {
    let model = sample();
    let bytes = model.to_bytes().unwrap();
    let n = u64::from_le_bytes(bytes[..8].try_into().unwrap()) as usize;
    let mut flipped = bytes.clone();
    flipped[8 + n + 3] ^= 0x10;
    let e = ReducedModel::from_bytes(&flipped, Path::new("b.rom")).unwrap_err();
    assert!(matches!(e, RomError::Damaged { .. }), "{e}");
    assert!(e.to_string().starts_with("b.rom: damaged"), "{e}");
    let mut nan = model.clone();
    nan.parts[0].k[(1, 2)] = f64::NAN;
    let e = ReducedModel::from_bytes(&nan.to_bytes().unwrap(), Path::new("n.rom"))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("array pad.K holds NaN at row 2, column 3"),
        "{e}"
    );
    // The same file with the checksum taken out of its header: the layout of a file of
    // an earlier squeal.
    let json: serde_json::Value = serde_json::from_slice(&bytes[8..8 + n]).unwrap();
    let mut squeal: serde_json::Value =
        serde_json::from_str(json["__metadata__"]["squeal"].as_str().unwrap()).unwrap();
    assert!(squeal["arrays_crc32"].is_string());
    squeal.as_object_mut().unwrap().remove("arrays_crc32");
    let mut table = json.clone();
    table["__metadata__"]["squeal"] = squeal.to_string().into();
    let mut text = serde_json::to_vec(&table).unwrap();
    text.resize(text.len().next_multiple_of(8), b' ');
    let mut old = (text.len() as u64).to_le_bytes().to_vec();
    old.extend(text);
    old.extend(&bytes[8 + n..]);
    let back = ReducedModel::from_bytes(&old, Path::new("old.rom")).unwrap();
    assert_eq!(back, model);
}

#[test]
fn round_trip_is_bit_exact() {
    let model = sample();
    let bytes = model.to_bytes().unwrap();
    let back = ReducedModel::from_bytes(&bytes, Path::new("mem.rom")).unwrap();
    assert_eq!(back, model);
    // Same model, same bytes: the file is deterministic.
    assert_eq!(model.to_bytes().unwrap(), bytes);
}

#[test]
fn rejects_garbage_and_truncation() {
    let bytes = sample().to_bytes().unwrap();
    for cut in [0, 4, 8, 40, bytes.len() - 1] {
        let r = ReducedModel::from_bytes(&bytes[..cut], Path::new("cut.rom"));
        assert!(matches!(r, Err(RomError::Format { .. })), "cut at {cut}");
    }
    let r = ReducedModel::from_bytes(b"not a model at all", Path::new("junk.rom"));
    assert!(matches!(r, Err(RomError::Format { .. })));
}

/// A file cut inside its arrays has a whole header; `read_header` (what the freshness
/// check reads) must still see that it is cut, or a cached model is called up to date and
/// then fails to load. Every cut from the end of the header on is caught; the whole file
/// passes.
#[test]
fn read_header_sees_a_file_cut_inside_its_arrays() {
    let bytes = sample().to_bytes().unwrap();
    let n = u64::from_le_bytes(bytes[..8].try_into().unwrap()) as usize;
    let dir = std::env::temp_dir().join(format!("squeal-rom-cut-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("cut.rom");
    std::fs::write(&path, &bytes).unwrap();
    assert!(read_header(&path).is_ok());
    for cut in [8 + n, 8 + n + 1, bytes.len() - 1] {
        std::fs::write(&path, &bytes[..cut]).unwrap();
        let e = read_header(&path).unwrap_err();
        assert!(
            matches!(e, RomError::Format { .. }) && e.to_string().contains("cut short"),
            "cut at {cut}: {e}"
        );
    }
    // The OS reason of a missing file appears once in the message (no source() repeat).
    let missing = dir.join("missing.rom");
    let e = ReducedModel::read(&missing).unwrap_err();
    assert!(std::error::Error::source(&e).is_none(), "{e}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The streamed reader: a basis of several read chunks (9000 x 120 values, 8.6 MB, against
/// chunks of 4 MB) comes back from the file bit for bit, each value where safetensors' own
/// reader of the same bytes puts it; a file with a byte appended after its arrays is refused
/// by both the reader and the header check (a file that is not what its header describes).
#[test]
fn streamed_read_of_several_chunks_matches_safetensors() {
    let mut model = sample();
    let (rows, cols) = (9000, 120);
    let part = &mut model.parts[0];
    part.info.full_dofs = rows;
    let basis = part.basis.as_mut().unwrap();
    basis.values = Mat::from_fn(rows, cols, |i, j| (i as f64).sin() * 1e3 + j as f64 * 0.25);
    basis.dof_node = (0..rows as u64).map(|i| i / 3 + 1).collect();
    basis.dof_dir = (0..rows).map(|i| (i % 3) as u8).collect();
    part.info.dofs = (0..cols).map(|mode| DofLabel::Mode { mode }).collect();
    part.k = Mat::from_fn(cols, cols, |i, j| (i + 2 * j) as f64);
    part.m = Mat::from_fn(cols, cols, |i, j| if i == j { 2.0 } else { 0.0 });
    let dir = std::env::temp_dir().join(format!("squeal-rom-chunks-{}", std::process::id()));
    let path = dir.join("big.rom");
    model.write(&path).unwrap();
    assert_eq!(ReducedModel::read(&path).unwrap(), model);
    let bytes = std::fs::read(&path).unwrap();
    let st = SafeTensors::deserialize(&bytes).unwrap();
    let t = st.tensor("pad.basis").unwrap();
    assert_eq!(t.shape(), [rows, cols]);
    let at = |i: usize, j: usize| {
        let k = 8 * (i * cols + j);
        f64::from_le_bytes(t.data()[k..k + 8].try_into().unwrap())
    };
    for (i, j) in [(0, 0), (4368, 119), (4369, 0), (8999, 77)] {
        assert_eq!(
            at(i, j).to_bits(),
            model.parts[0].basis.as_ref().unwrap().values[(i, j)].to_bits()
        );
    }
    let mut longer = bytes.clone();
    longer.push(b' ');
    std::fs::write(&path, &longer).unwrap();
    for e in [
        ReducedModel::read(&path).unwrap_err(),
        read_header(&path).unwrap_err(),
    ] {
        assert!(
            matches!(e, RomError::Format { .. }) && e.to_string().contains("1 byte follow"),
            "{e}"
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
