//! `--mic x,y,z` (issue 23): `squeal chbm`, `squeal branch` and `squeal run` take the sound at
//! the microphones given instead of the default one, and refuse a position that is not three
//! numbers or that lies inside the brake, saying what to do. On the bundled coarse brake.

use super::common;
use common::{bundled_scene, run_ok, squeal, temp_dir};

/// The `(position, dB(A), ERP dB)` of every `sound:` line `squeal chbm` prints.
fn sound_lines(text: &str) -> Vec<(String, f64, f64)> {
    text.lines()
        .filter_map(|l| l.trim().strip_prefix("sound: "))
        .map(|l| {
            let level = l.split(" dB(A)").next().unwrap().parse().unwrap();
            let at = l.split("microphone ").nth(1).unwrap();
            let position = at[..at.find(" m ").unwrap()].to_string();
            let erp = l.split("ERP ").nth(1).unwrap().split(' ').next().unwrap();
            (position, level, erp.parse().unwrap())
        })
        .collect()
}

#[test]
fn microphones_from_the_command_line() {
    let dir = temp_dir("mic", "flag");
    let scene = dir.join("brake.toml");
    std::fs::write(&scene, bundled_scene("coarse")).unwrap();
    let (s, out) = (scene.to_str().unwrap(), dir.join("out"));
    let o = out.to_str().unwrap();

    // The default microphone, then two given ones and the default position given back, as
    // printed (to 1 mm), in one run (each microphone's level is its own Rayleigh integral of
    // the same cycle: a third microphone changes neither of the others).
    let default = sound_lines(&run_ok(&["chbm", s, "-o", o, "--no-vtu"]));
    assert_eq!(default.len(), 1, "{default:?}");
    let (position, level, erp) = default[0].clone();
    let xyz = position
        .trim_matches(|c| c == '(' || c == ')')
        .replace(' ', "");
    let given = run_ok(&[
        "chbm",
        s,
        "-o",
        o,
        "--no-vtu",
        "--mic",
        "-0.35,0,0.35",
        "--mic",
        "0.35,0,0.35",
        "--mic",
        &xyz,
    ]);
    let lines = sound_lines(&given);
    assert_eq!(lines.len(), 3, "{given}");
    assert_eq!(lines[0].0, "(-0.350, 0.000, 0.350)");
    assert_eq!(lines[1].0, "(0.350, 0.000, 0.350)");
    // The radiated power does not depend on where one listens: the same digits.
    assert!(lines.iter().all(|l| l.2 == erp), "{lines:?} vs {erp}");
    // The two sides of the disc differ (the pad and its mode are on one side): measured
    // 116.8 and 111.5 dB(A).
    assert!((lines[0].1 - lines[1].1).abs() > 1.0, "{lines:?}");
    // The default position given back: the same level to the printed 0.1 dB (1 mm at 0.5 m
    // moves the level by under 0.02 dB).
    assert!(
        (lines[2].1 - level).abs() <= 0.1 + 1e-9,
        "{lines:?} vs {level}"
    );

    // The branch's levels at the given microphone, named in the text and in branch.json: the
    // levels are the cycles' (`sound::squeal_level_text`), so the tori past the
    // Neimark–Sacker point are not followed (`--no-torus`). With them, and the third `chbm`
    // run above on its own, this test took 134 s on one thread; 17 s now (2026-11-28, load
    // average 3.2–3.4 both times).
    let branch = run_ok(&["branch", s, "-o", o, "--mic", "-0.35,0,0.35", "--no-torus"]);
    assert!(
        branch.contains("sound at the microphone (-0.350, 0.000, 0.350) m (Rayleigh integral"),
        "{branch}"
    );
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("branch/branch.json")).unwrap())
            .unwrap();
    assert_eq!(json["microphone_m"], serde_json::json!([-0.35, 0.0, 0.35]));

    // Bad input: the usage error (exit 2) names what to give; a microphone inside the brake
    // is refused (exit 1) before the sweep, with the brake's bounds and the default position.
    for (cmd, mic, code, said) in [
        (
            "chbm",
            "0.3,0",
            2,
            "'0.3,0' has 2 value(s): give the microphone's position as three numbers in metres",
        ),
        (
            "branch",
            "0.3,x,0",
            2,
            "'x' in '0.3,x,0' is not a finite number",
        ),
        ("run", "0,0,inf", 2, "is not a finite number"),
        (
            "branch",
            "0,0,0.01",
            1,
            "--mic: microphone 1 at (0, 0, 0.01) m is inside the brake's bounds",
        ),
        (
            "run",
            "0.1,0.05,0",
            1,
            "place it in the air around the brake, e.g. the default",
        ),
    ] {
        let r = squeal(&[cmd, s, "-o", o, "--mic", mic]);
        let err = String::from_utf8_lossy(&r.stderr);
        assert_eq!(r.status.code(), Some(code), "{cmd} --mic {mic}: {err}");
        assert!(err.contains(said), "{cmd} --mic {mic}: {err}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// `[sound]` in the scene (issue 23: microphones and air from the scene): its microphone is
/// used as `--mic` would be, in the scene's length unit; the air's density scales the radiated
/// power (ERP = ½ ρ c Σ A v_n², so twice the density is +3.01 dB); values that are not air are
/// refused at the key's line.
#[test]
fn microphones_and_air_from_the_scene() {
    let dir = temp_dir("mic", "scene");
    let base = bundled_scene("coarse");
    let o = dir.join("out");
    let o = o.to_str().unwrap();
    let write = |name: &str, extra: &str| {
        let p = dir.join(name);
        std::fs::write(&p, format!("{base}\n{extra}\n")).unwrap();
        p.to_str().unwrap().to_string()
    };
    let flag = sound_lines(&run_ok(&[
        "chbm",
        &write("plain.toml", ""),
        "-o",
        o,
        "--no-vtu",
        "--mic",
        "0.35,0,0.35",
    ]));
    let scene = sound_lines(&run_ok(&[
        "chbm",
        &write("mic.toml", "[sound]\nmicrophones = [[0.35, 0.0, 0.35]]"),
        "-o",
        o,
        "--no-vtu",
    ]));
    // The same position, the same cycle: the same printed level and ERP.
    assert_eq!(scene, flag, "scene {scene:?} vs --mic {flag:?}");
    let dense = sound_lines(&run_ok(&[
        "chbm",
        &write(
            "air.toml",
            "[sound]\nmicrophones = [[0.35, 0.0, 0.35]]\nair_density = 2.4",
        ),
        "-o",
        o,
        "--no-vtu",
    ]));
    // 10 log10(2) = 3.0103 dB, to the two printed values' 0.05 dB each.
    assert!(
        (dense[0].2 - flag[0].2 - 3.0103).abs() <= 0.1 + 1e-9,
        "{dense:?} vs {flag:?}"
    );
    // The disc alone radiates less power than the disc and the pad (the pad's faces add
    // their share, never cancel in the ERP's sum of squares).
    let disc = sound_lines(&run_ok(&[
        "chbm",
        &write(
            "disc.toml",
            "[sound]\nmicrophones = [[0.35, 0.0, 0.35]]\nradiating = [\"disc\"]",
        ),
        "-o",
        o,
        "--no-vtu",
    ]));
    assert!(disc[0].2 < flag[0].2, "disc alone {disc:?} vs all {flag:?}");
    for (extra, said) in [
        ("[sound]\nradiating = [\"caliper\"]", "its parts: disc, pad"),
        ("[sound]\nair_density = -1.0", "sound.air_density"),
        ("[sound]\nspeed_of_sound = 1e9", "sound.speed_of_sound"),
        ("[sound]\nmicrophones = []", "sound.microphones"),
        (
            "[sound]\nmicrophones = [[0.0, 0.0, 0.0]]",
            "inside the brake",
        ),
    ] {
        let p = write("bad.toml", extra);
        let out = squeal(&["chbm", &p, "-o", o, "--no-vtu"]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{extra}: {err}");
        assert!(err.contains(said), "{extra}: {err}");
        assert!(err.contains("bad.toml:"), "{extra}: no file:line in {err}");
    }
}
