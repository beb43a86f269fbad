//! Issue 12 ("never lose a user's file, say what failed where"): what the command line refuses
//! before any work, and what its messages say. Each case failed before the fix: the commands
//! exited 0 and wrote over their input, or ran the reduction before rejecting an argument.

use super::common;

use common::{bundled_scene, root, run_ok, squeal, temp_dir};
use std::path::Path;
use std::process::Output;

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// A copy of a bundled mesh in `dir`.
fn copy_mesh(dir: &Path, name: &str) -> std::path::PathBuf {
    let to = dir.join(name);
    std::fs::copy(root().join("meshes").join(name), &to).unwrap();
    to
}

#[test]
fn no_command_writes_over_its_input_or_into_a_misnamed_file() {
    let dir = temp_dir("trust", "inputs");
    let pad = copy_mesh(&dir, "pad_coarse.inp");
    let disc = copy_mesh(&dir, "disc_coarse.inp");
    let original = std::fs::read(&pad).unwrap();
    let (pad_s, disc_s) = (pad.to_str().unwrap(), disc.to_str().unwrap());
    let vtk = dir.join("y.vtk");
    let txt = dir.join("file.txt");
    for (args, says) in [
        // The mesh itself as the output of a conversion.
        (vec!["mesh", "convert", pad_s, pad_s], "must end in .vtu"),
        // VTU XML into a .vtk file (legacy VTK readers fail on it).
        (
            vec!["mesh", "convert", pad_s, vtk.to_str().unwrap()],
            "must end in .vtu",
        ),
        // The pad mesh as the reduced model.
        (
            vec!["reduce", disc_s, pad_s, "-o", pad_s],
            "must end in .rom",
        ),
        // A file name as the folder of fe export.
        (
            vec!["fe", "export", pad_s, "-o", txt.to_str().unwrap()],
            "is a folder",
        ),
    ] {
        let o = squeal(&args);
        assert_eq!(o.status.code(), Some(1), "{args:?}: {}", stderr(&o));
        assert!(stderr(&o).contains(says), "{args:?}: {}", stderr(&o));
    }
    assert_eq!(
        std::fs::read(&pad).unwrap(),
        original,
        "the pad mesh changed"
    );
    assert!(!vtk.exists() && !txt.exists());

    // A .rom that is a hard link to the mesh has the right extension but is the mesh.
    let link = dir.join("pad.rom");
    std::fs::hard_link(&pad, &link).unwrap();
    let o = squeal(&["reduce", disc_s, pad_s, "-o", link.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("pad mesh this command reads"),
        "{}",
        stderr(&o)
    );
    assert_eq!(
        std::fs::read(&pad).unwrap(),
        original,
        "the pad mesh changed"
    );

    // A scene whose reduced model would replace its disc mesh.
    let scene = dir.join("scene.toml");
    let text = bundled_scene("coarse").replace(
        "modes = 50",
        &format!("modes = 50\nrom = {:?}", disc.display().to_string()),
    );
    std::fs::write(&scene, text).unwrap();
    let o = squeal(&[
        "stability",
        scene.to_str().unwrap(),
        "-o",
        dir.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("must end in .rom"), "{}", stderr(&o));
    let _ = std::fs::remove_dir_all(&dir);
}

/// Bad arguments are rejected in well under the time of a reduction (about 1.5 s on the
/// coarse meshes, and nothing is written into the output folder).
#[test]
fn bad_arguments_fail_before_any_work() {
    let dir = temp_dir("trust", "arguments");
    let scene = dir.join("scene.toml");
    std::fs::write(&scene, bundled_scene("coarse")).unwrap();
    let s = scene.to_str().unwrap();
    let out = dir.join("out");
    let o_s = out.to_str().unwrap();
    let blocked = dir.join("blocked");
    std::fs::write(&blocked, b"a file where a folder is needed").unwrap();
    let unwritable = blocked.join("out");
    for (args, says) in [
        (
            vec!["chbm", s, "--mu-ratio", "0.9", "--guessed-start", "-o", o_s],
            "--mu-ratio 0.9",
        ),
        (vec!["chbm", s, "--mu-ratio=0", "-o", o_s], "--mu-ratio 0"),
        (vec!["chbm", s, "--mu", "nan", "-o", o_s], "--mu NaN"),
        (
            vec!["stability", s, "--mu", "1..0/201", "-o", o_s],
            "start must be below end",
        ),
        (
            vec!["stability", s, "--mu", "0:0.5:100", "-o", o_s],
            "ambiguous",
        ),
        // Issue 22: a negative friction sweep named one mode twice as the pair.
        (
            vec!["stability", s, "--mu=-1..1/201", "-o", o_s],
            "friction -1 is negative",
        ),
        (
            vec!["stability", s, "-o", unwritable.to_str().unwrap()],
            "blocked",
        ),
        (
            vec![
                "study",
                s,
                "--kind",
                "mesh",
                "--levels",
                "coarse,huge",
                "-o",
                o_s,
            ],
            "disc_huge.inp",
        ),
    ] {
        let t = std::time::Instant::now();
        let o = squeal(&args);
        let secs = t.elapsed().as_secs_f64();
        assert_eq!(o.status.code(), Some(1), "{args:?}: {}", stderr(&o));
        assert!(stderr(&o).contains(says), "{args:?}: {}", stderr(&o));
        // A reduction of the coarse brake alone takes over a second; a check takes
        // milliseconds. 1 s leaves room for a loaded machine.
        assert!(secs < 1.0, "{args:?} took {secs:.2} s");
        assert!(
            !out.join("brake.rom").exists(),
            "{args:?} reduced the brake first"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// Errors name the file once: the OS reason of a missing scene appears once, and a mesh
/// error in the reduction names the mesh.
#[test]
fn errors_name_the_file_and_print_each_reason_once() {
    let dir = temp_dir("trust", "messages");
    let o = squeal(&["stability", dir.join("missing.toml").to_str().unwrap()]);
    let e = stderr(&o);
    let os = std::io::Error::from(std::io::ErrorKind::NotFound).to_string();
    assert!(e.contains("missing.toml"), "{e}");
    assert_eq!(e.matches("(os error 2)").count(), 1, "{e} ({os})");

    let pad = copy_mesh(&dir, "pad_coarse.inp");
    let disc = copy_mesh(&dir, "disc_coarse.inp");
    let text = std::fs::read_to_string(&pad)
        .unwrap()
        .replace("*NSET, NSET=PISTON", "*NSET, NSET=PISTONS");
    std::fs::write(&pad, text).unwrap();
    let o = squeal(&[
        "reduce",
        disc.to_str().unwrap(),
        pad.to_str().unwrap(),
        "-o",
        dir.join("b.rom").to_str().unwrap(),
    ]);
    let e = stderr(&o);
    assert!(
        e.contains("pad_coarse.inp: node set PISTON is missing"),
        "{e}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// `mesh info --material` checks what `reduce` checks, and says which materials it used.
#[test]
fn mesh_info_checks_material_overrides() {
    let pad = root().join("meshes/pad_coarse.inp");
    let p = pad.to_str().unwrap();
    for (material, says) in [
        ("LINNING=2e9,0.25,2500", "no element set LINNING"),
        ("LINING=-2e9,0.25,2500", "not positive definite"),
        ("LINING=2e9,0.6,2500", "not positive definite"),
    ] {
        let o = squeal(&["mesh", "info", p, "--material", material]);
        assert_eq!(o.status.code(), Some(1), "{material}: {}", stderr(&o));
        assert!(stderr(&o).contains(says), "{material}: {}", stderr(&o));
    }
    let msh = root().join("meshes/pad_coarse.msh");
    let o = squeal(&[
        "mesh",
        "info",
        msh.to_str().unwrap(),
        "--material",
        "LINING=2e9,0.25,2500",
        "--material",
        "BACKPLATE=210e9,0.3,7850",
    ]);
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(!text.contains("none in the file"), "{text}");
    assert!(text.contains("given with --material"), "{text}");
    // The bundled pad's mass with these materials: 0.120 kg lining + 0.188 kg backplate.
    assert!(text.contains("mass      3.0837"), "{text}");
}

/// Exit codes are documented and distinct: 2 is a usage error only, 4 a mesh with errors.
#[test]
fn exit_codes_are_distinct_and_documented() {
    let o = squeal(&["--help"]);
    let help = String::from_utf8_lossy(&o.stdout);
    for line in [
        "2  a usage error",
        "3  chbm, run",
        "4  mesh info",
        "101  an internal error",
        "130  interrupted (Ctrl-C)",
        "141  the standard output was closed",
    ] {
        assert!(help.contains(line), "{help}");
    }
    assert_eq!(squeal(&["mesh", "info"]).status.code(), Some(2));
    let dir = temp_dir("trust", "exit");
    let pad = copy_mesh(&dir, "pad_coarse.inp");
    // Element 198 with two corners swapped: inverted.
    let text = std::fs::read_to_string(&pad).unwrap().replace(
        "198, 157, 465, 437, 639, 984, 985, 986, 654, 988, 987",
        "198, 465, 157, 437, 639, 984, 986, 985, 988, 654, 987",
    );
    std::fs::write(&pad, text).unwrap();
    let o = squeal(&["mesh", "info", pad.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(4), "{}", stderr(&o));
    let _ = std::fs::remove_dir_all(&dir);
}

/// `squeal mesh info --scene`: what the scene selects, with the areas of the bundled sets, a
/// VTU with a flag per set, and the refusals (a .vtu over the scene, --material with --scene).
#[test]
fn mesh_info_lists_what_a_scene_selects() {
    let dir = temp_dir("trust", "scene-info");
    let scene = dir.join("scene.toml");
    let extra = "\n[sets.disc]\nclamp = { plane = { point = [0, 0, -0.035], normal = [0, 0, 1] }, facing = [0, 0, -1] }\n";
    std::fs::write(&scene, bundled_scene("coarse") + extra).unwrap();
    let s = scene.to_str().unwrap();
    let vtu = dir.join("sets.vtu");
    let o = squeal(&["mesh", "info", "--scene", s, "--vtu", vtu.to_str().unwrap()]);
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", stderr(&o));
    // The clamp from the scene's line 2 of the appended text; the rest from the meshes' sets.
    // Areas: the flange seat pi (0.086^2 - 0.033^2) = 1.9812e-2 m^2 (the coarse mesh's
    // quadratic faces give 1.981537e-2), the footprint 4.80e-3 m^2 (README).
    assert!(text.contains("sets.disc.clamp (scene, "), "{text}");
    assert!(text.contains("area 1.981537e-2"), "{text}");
    assert!(text.contains("sets.pad.friction_face (the mesh's node set): set CONTACT_FACE"));
    assert!(text.contains("area 4.799658e-3"), "{text}");
    let written = std::fs::read_to_string(&vtu).unwrap();
    for flag in [
        "set:disc:clamp",
        "set:pad:pistons",
        "set:pad:abutments",
        "set:pad",
    ] {
        assert!(written.contains(&format!("Name=\"{flag}\"")), "{flag}");
    }
    let o = squeal(&["mesh", "info", "--scene", s, "--vtu", s]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("must end in .vtu"), "{}", stderr(&o));
    let o = squeal(&[
        "mesh",
        "info",
        "--scene",
        s,
        "--material",
        "DISC=1e11,0.3,7000",
    ]);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).contains("does not go with --scene"),
        "{}",
        stderr(&o)
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// Issue 22: a mistake in a mesh gives an error, never a plausible wrong mu0. A piston id
/// mistyped in the PISTON set (the reader drops the member: 3 pistons, mu0 0.7018 instead of
/// 0.4618 on these meshes) and an element naming an undefined node (the reader drops the
/// element) are refused by `reduce` and by a scene's run, before any reduction, naming the
/// file, the set or finding and what to do.
#[test]
fn mesh_mistakes_are_refused_not_analysed() {
    let dir = temp_dir("trust", "mesh-mistakes");
    let disc = copy_mesh(&dir, "disc_coarse.inp");
    let text = std::fs::read_to_string(root().join("meshes/pad_coarse.inp")).unwrap();
    let piston = dir.join("pad_piston.inp");
    std::fs::write(
        &piston,
        text.replace(
            "*NSET, NSET=PISTON\n34, 35, 36, 37",
            "*NSET, NSET=PISTON\n34, 35, 36, 99937",
        ),
    )
    .unwrap();
    let element = dir.join("pad_element.inp");
    std::fs::write(
        &element,
        text.replace(
            "198, 157, 465, 437, 639, 984, 985, 986, 654, 988, 987",
            "198, 999157, 465, 437, 639, 984, 985, 986, 654, 988, 987",
        ),
    )
    .unwrap();
    let d = disc.to_str().unwrap();
    for (pad, says) in [
        (
            &piston,
            "node set PISTON names 1 node id(s) the file never defines (99937)",
        ),
        (
            &element,
            "1 element(s) reference 1 node id(s) that are not defined (e.g. node 999157); they were left out (element ids 198)",
        ),
    ] {
        let file = pad.file_name().unwrap().to_str().unwrap();
        let rom = dir.join("b.rom");
        let o = squeal(&[
            "reduce",
            d,
            pad.to_str().unwrap(),
            "-o",
            rom.to_str().unwrap(),
        ]);
        assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
        assert!(
            stderr(&o).contains(&format!("{file}: {says}")),
            "{}",
            stderr(&o)
        );
        assert!(!rom.exists());
        let scene = dir.join("scene.toml");
        let bundled = bundled_scene("coarse");
        let pad_line = bundled.lines().find(|l| l.starts_with("pad = ")).unwrap();
        let text = bundled.replace(pad_line, &format!("pad = {:?}", pad.display().to_string()));
        std::fs::write(&scene, text).unwrap();
        let out = dir.join("out");
        let t = std::time::Instant::now();
        let o = squeal(&[
            "stability",
            scene.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
        ]);
        assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
        assert!(
            stderr(&o).contains(file) && stderr(&o).contains(says),
            "{}",
            stderr(&o)
        );
        // Refused on reading, not after a reduction (over a second on these meshes).
        assert!(t.elapsed().as_secs_f64() < 1.0);
        assert!(!out.join("brake.rom").exists());
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// Issue 22: a thread count far above the cores is refused (it would start that many
/// threads); 0 is all cores. A mesh file's material no material has is an ERROR of `mesh
/// info` (exit 4), not "no findings".
#[test]
fn thread_counts_and_file_materials_are_checked() {
    let pad = root().join("meshes/pad_coarse.inp");
    let p = pad.to_str().unwrap();
    let o = squeal(&["--threads", "100000", "mesh", "info", p]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("100000 threads on"), "{}", stderr(&o));
    let o = squeal(&["--threads", "0", "mesh", "info", p]);
    assert!(o.status.success(), "{}", stderr(&o));
    let dir = temp_dir("trust", "materials");
    let text = std::fs::read_to_string(&pad).unwrap();
    for (from, to, says) in [
        (
            "*ELASTIC\n2e+09, 0.25",
            "*ELASTIC\n-2e+09, 0.25",
            "not positive definite",
        ),
        (
            "*ELASTIC\n2e+09, 0.25",
            "*ELASTIC\n2e+09, 0.5",
            "not positive definite",
        ),
        (
            "*DENSITY\n2500",
            "*DENSITY\n0",
            "density 0 kg/m^3 is not positive",
        ),
    ] {
        assert!(text.contains(from), "{from}");
        let bad = dir.join("pad.inp");
        std::fs::write(&bad, text.replacen(from, to, 1)).unwrap();
        let o = squeal(&["mesh", "info", bad.to_str().unwrap()]);
        let out = String::from_utf8_lossy(&o.stdout);
        assert_eq!(o.status.code(), Some(4), "{to}: {out}");
        assert!(
            out.contains("ERROR: material FRICTION_LINING") && out.contains(says),
            "{out}"
        );
        assert!(!out.contains("no findings"), "{out}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// Issue 22 on the coarse brake, one reduction for four runs: the damping used is said with
/// where it comes from (the scene's line, or the default); a cached `.rom` with one flipped
/// bit is rebuilt, saying so, and gives the same mu0 as before; a linear contact law gives
/// l1 = 0, called degenerate (not subcritical), and `branch` says what to add.
#[test]
fn damping_is_said_damaged_models_rebuilt_and_degenerate_points_named() {
    let dir = temp_dir("trust", "rom-damping");
    let scene = dir.join("scene.toml");
    let text = bundled_scene("coarse").replace("mu = \"0..1/201\"", "mu = \"0.40..0.50/11\"");
    let line = text
        .lines()
        .position(|l| l.starts_with("global_ratio"))
        .unwrap()
        + 1;
    std::fs::write(&scene, &text).unwrap();
    let (s, out) = (scene.to_str().unwrap(), dir.join("out"));
    let o_s = out.to_str().unwrap();
    let first = run_ok(&["stability", s, "-o", o_s, "--no-vtu"]);
    let said = format!(
        "damping: modal ratio 0.01 (1 %) on every mode ({s}:{line}), plus 0.001 and 0.001 on the pair"
    );
    assert!(first.contains(&said), "{first}");
    let mu0 = |t: &str| {
        t.lines()
            .find(|l| l.starts_with("Hopf point mu0 = "))
            .map(|l| l.split_whitespace().nth(4).unwrap().to_string())
            .unwrap()
    };
    let summary = std::fs::read_to_string(out.join("stability/summary.json")).unwrap();
    assert!(summary.contains("\"global_ratio_from\""), "{summary}");

    // One bit of the arrays (past the header, in the middle of the file) flipped.
    let rom = out.join("brake.rom");
    let mut bytes = std::fs::read(&rom).unwrap();
    let at = bytes.len() / 2;
    bytes[at] ^= 0x04;
    std::fs::write(&rom, &bytes).unwrap();
    let default = text.replace("global_ratio = 0.01\n", "");
    std::fs::write(&scene, &default).unwrap();
    let o = squeal(&["stability", s, "-o", o_s, "--no-vtu"]);
    let (second, log) = (String::from_utf8_lossy(&o.stdout), stderr(&o));
    assert!(o.status.success(), "{log}");
    let all = format!("{log}{second}");
    assert!(
        all.contains("damaged reduced-model file") && all.contains("reducing again"),
        "{all}"
    );
    assert!(!all.contains("(up to date)"), "{all}");
    assert_eq!(mu0(&second), mu0(&first), "{second}");
    assert!(
        second.contains(&format!(
            "(the default: {s} gives no [damping] global_ratio)"
        )),
        "{second}"
    );

    // Eq (8) without its cubic term, stiffer than the curve's linear part so that the
    // sweep finds a Hopf point (mu0 = 0.5461 at 4842 Hz over mu = 0..1/101).
    let linear = text
        .replace(
            "compression_curve = {",
            "k_linear_per_area = 5.0e10\nk_cubic_per_area = 0.0\n# compression_curve = {",
        )
        .replace("0.40..0.50/11", "0.50..0.60/11");
    std::fs::write(&scene, &linear).unwrap();
    let third = run_ok(&["stability", s, "-o", o_s, "--no-vtu"]);
    assert!(third.contains("Hopf point is degenerate"), "{third}");
    assert!(third.contains("add a cubic contact stiffness"), "{third}");
    let o = squeal(&["branch", s, "-o", o_s]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("l1 = 0: the normal form is degenerate"),
        "{}",
        stderr(&o)
    );

    // A list of initial gaps that does not match the pairs: the error names the key's line.
    let gaps = text.replace(
        "normal = [0.0, 0.0, 1.0]",
        "normal = [0.0, 0.0, 1.0]\ninitial_gap = [1.0e-6, 1.0e-6]",
    );
    let gap_line = gaps
        .lines()
        .position(|l| l.starts_with("initial_gap"))
        .unwrap()
        + 1;
    std::fs::write(&scene, &gaps).unwrap();
    let o = squeal(&["stability", s, "-o", o_s, "--no-vtu"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let says = format!(
        "{s}:{gap_line}: contact.initial_gap: 2 initial gaps are given for 9 contact pairs"
    );
    assert!(stderr(&o).contains(&says), "{}", stderr(&o));

    // A damping pair beyond the brake's 158 modes: the error names the key's line.
    let pair = text.replace("pair = \"auto\"", "pair = [200, 201]");
    let pair_line = pair
        .lines()
        .position(|l| l.starts_with("pair = ["))
        .unwrap()
        + 1;
    std::fs::write(&scene, &pair).unwrap();
    let o = squeal(&["stability", s, "-o", o_s, "--no-vtu"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(
        stderr(&o).contains(&format!("{s}:{pair_line}: damping.pair: ")),
        "{}",
        stderr(&o)
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// Issue 22: a part left free says its restraints as the scene wrote them, not a Rust debug
/// dump (`Restraint { nodes: Set(...) }`). The disc clamped axially only turns and slides
/// in its plane: refused before any reduction, naming those three motions (issue 21, item 4;
/// before, "K_II is singular" after the disc's assembly and factorization).
#[test]
fn a_free_part_names_its_restraints_as_written() {
    let dir = temp_dir("trust", "free-part");
    let scene = dir.join("scene.toml");
    let text = bundled_scene("coarse") + "\n[sets.disc]\nclamp_hold = [\"axial\"]\n";
    std::fs::write(&scene, text).unwrap();
    let rom = dir.join("b.rom");
    let o = squeal(&[
        "reduce",
        "--scene",
        scene.to_str().unwrap(),
        "-o",
        rom.to_str().unwrap(),
    ]);
    let e = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{e}");
    for says in [
        "disc: the part is not held",
        "node set CLAMP held axial",
        "3 rigid-body motion(s) free: rotation about z through (",
        "translation along x; translation along y",
    ] {
        assert!(e.contains(says), "{says}: {e}");
    }
    assert!(!e.contains("Restraint {") && !e.contains("Set("), "{e}");
    let _ = std::fs::remove_dir_all(&dir);
}

// Issue 22: lost or mixed work.

/// `squeal <args>` run in the folder `dir`.
fn squeal_in(dir: &Path, args: &[&str]) -> Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_squeal"))
        .args(args)
        .current_dir(dir)
        .output()
        .unwrap()
}

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// The two bundled scenes are both `brake.toml`: their default output folders differ (before,
/// both were `out/brake`, and the second run replaced the first's reduced model and
/// stability figures). Below μ0 (0.4618 for one pad, 0.1268 for two on the coarse meshes)
/// the brake is stable, which is
/// the answer, exit 0 and the verdict on the first line after the reduction's log (before,
/// `pair = "auto"` with pair damping made it the error "the coalescing pair could not be
/// picked automatically").
#[test]
fn scenes_of_one_name_get_their_own_folders_and_a_stable_brake_is_an_answer() {
    let dir = temp_dir("trust", "default-out");
    std::fs::create_dir_all(dir.join("meshes/two_pad")).unwrap();
    std::fs::write(dir.join("meshes/brake.toml"), bundled_scene("coarse")).unwrap();
    std::fs::write(
        dir.join("meshes/two_pad/brake.toml"),
        common::two_pad_scene("coarse"),
    )
    .unwrap();
    for (scene, out) in [
        ("meshes/brake.toml", "out/meshes/brake"),
        ("meshes/two_pad/brake.toml", "out/meshes/two_pad/brake"),
    ] {
        let o = squeal_in(&dir, &["stability", scene, "--mu", "0..0.1/5", "--no-vtu"]);
        assert!(o.status.success(), "{scene}: {}{}", stdout(&o), stderr(&o));
        // The first line after the reduction's log.
        let text = stdout(&o);
        let first = text
            .lines()
            .find(|l| !l.starts_with("reduced model") && !l.starts_with("  "))
            .unwrap_or_default();
        assert!(
            first.starts_with("stable for mu in [0, 0.1]: no mode in the band goes unstable"),
            "{scene}: {text}"
        );
        let out = dir.join(out);
        assert!(out.join("brake.rom").is_file(), "{}", out.display());
        assert!(out.join("stability/stability.csv").is_file());
    }
    assert!(!dir.join("out/brake").exists());
    let _ = std::fs::remove_dir_all(&dir);
}

/// A folder holding a user's own files is refused before any work unless `--force`; a folder
/// another run holds (the test holds its lock) is refused naming the holder's host and pid;
/// another machine's lock is reported and left alone; a killed run's lock is taken over and
/// the manifest says that run did not finish.
#[cfg(target_os = "linux")]
#[test]
fn output_folders_are_locked_claimed_and_never_taken_from_a_user() {
    let dir = temp_dir("trust", "folder");
    let scene = dir.join("scene.toml");
    std::fs::write(&scene, bundled_scene("coarse")).unwrap();
    let s = scene.to_str().unwrap();
    let out = dir.join("out");
    let o_s = out.to_str().unwrap();
    let quick = ["stability", s, "--mu", "0..0.1/2", "--no-vtu", "-o", o_s];

    // A user's own notes where the report would go (`-o .` in a project folder).
    std::fs::create_dir_all(&out).unwrap();
    std::fs::write(out.join("index.md"), b"my notes").unwrap();
    let t = std::time::Instant::now();
    let o = squeal(&quick);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("holds 1 file(s) that no squeal run wrote (index.md)")
            && stderr(&o).contains("--force"),
        "{}",
        stderr(&o)
    );
    // Refused before the reduction (over a second on these meshes).
    assert!(t.elapsed().as_secs_f64() < 1.0 && !out.join("brake.rom").exists());
    let o = squeal(&[&quick[..], &["--force"]].concat());
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(std::fs::read(out.join("index.md")).unwrap(), b"my notes");
    std::fs::remove_file(out.join("index.md")).unwrap();
    // The manifest claims what the run wrote: the next run needs no --force.
    let manifest: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("squeal-manifest.json")).unwrap())
            .unwrap();
    assert_eq!(manifest["runs"][0]["status"], "finished");
    assert_eq!(manifest["files"]["stability/stability.csv"]["run"], 1);
    assert_eq!(
        manifest["runs"][0]["scene_sha256"].as_str().unwrap().len(),
        64
    );
    assert!(squeal(&quick).status.success());

    // A run holds the folder: the test takes the lock as a run would.
    let lock_path = out.join(".squeal-lock");
    let me = format!(
        "{{\"host\":\"testhost\",\"boot\":\"0\",\"pid_ns\":\"0\",\"pid\":{},\"started\":\"now\",\"command\":\"squeal run held\"}}",
        std::process::id()
    );
    std::fs::write(&lock_path, &me).unwrap();
    let lock = std::fs::File::open(&lock_path).unwrap();
    lock.try_lock().unwrap();
    let o = squeal(&quick);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(
        stderr(&o).contains(&format!(
            "another squeal run is writing into this folder (host testhost, pid {}",
            std::process::id()
        )),
        "{}",
        stderr(&o)
    );
    drop(lock);

    // Another machine's lock: reported, not taken.
    let other = "{\"host\":\"node_7\",\"boot\":\"0123456789ab\",\"pid_ns\":\"1\",\"pid\":4242,\"started\":\"then\",\"command\":\"squeal run there\"}";
    std::fs::write(&lock_path, other).unwrap();
    let o = squeal(&quick);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("on host node_7 (pid 4242"),
        "{}",
        stderr(&o)
    );
    assert_eq!(std::fs::read_to_string(&lock_path).unwrap(), other);
    std::fs::remove_file(&lock_path).unwrap();

    // A run killed mid-way (SIGKILL, as a lost node or an impatient kill -9).
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_squeal"))
        .args(["stability", s, "--mu", "0..1/401", "-o", o_s])
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    let running = |m: &str| m.contains("\"status\": \"running\"");
    let t = std::time::Instant::now();
    while !std::fs::read_to_string(out.join("squeal-manifest.json")).is_ok_and(|m| running(&m)) {
        assert!(t.elapsed().as_secs() < 60, "the run never started");
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    child.kill().unwrap();
    child.wait().unwrap();
    assert!(lock_path.exists());
    let o = squeal(&quick);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("took over the lock of a run that is gone")
            && stderr(&o).contains("did not finish"),
        "{}",
        stderr(&o)
    );
    assert!(!lock_path.exists());
    let _ = std::fs::remove_dir_all(&dir);
}
