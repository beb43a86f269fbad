//! Finished reductions kept when another part fails (issue 21, item 4;
//! `squeal_reduce::brake::reduce_brake_keeping`): the coarse brake whose pad fails in its
//! reduction (a tie whose slave face lies far from its master) keeps the disc, and the run
//! after the fix takes it instead of reducing it again — the same bits as a reduction from
//! scratch; a kept part that no longer stands for the part as asked for is reduced again.

use super::common;

use common::{coarse, coarse_inputs};
use squeal_reduce::brake::{
    BrakeInputs, ModeChoice, forget_kept, kept_dir, reduce_brake_keeping, reduce_brake_loaded,
};
use squeal_reduce::craig_bampton::Stage;
use squeal_reduce::rom::InterfaceKind;
use squeal_reduce::tie::Tie;

fn inputs() -> BrakeInputs {
    BrakeInputs {
        modes: ModeChoice::Fixed(20),
        ..coarse_inputs(InterfaceKind::Patch)
    }
}

#[test]
fn a_failed_pad_keeps_the_finished_disc_and_the_next_run_takes_it() {
    let dir = std::env::temp_dir().join(format!("squeal-kept-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let keep = kept_dir(&dir.join("brake.rom"));
    assert_eq!(keep, dir.join("brake.rom.parts"));
    forget_kept(&keep).unwrap();
    let good = inputs();
    let mut bad = good.clone();
    bad.pads[0].part.ties.push(Tie {
        slave: "CONTACT_FACE".into(),
        master: "ABUTMENT".into(),
        tolerance: Some(1e-6),
    });
    let run = |inputs: &BrakeInputs| {
        let mut stages = Vec::new();
        let r = reduce_brake_keeping(
            inputs,
            coarse("disc"),
            vec![coarse("pad")],
            Some(&keep),
            &mut |part, stage| stages.push((part.to_string(), stage)),
        );
        (r, stages)
    };
    let (failed, _) = run(&bad);
    let e = failed.unwrap_err().to_string();
    assert!(e.contains("tie of CONTACT_FACE (slave) to ABUTMENT"), "{e}");
    assert!(
        keep.join("disc.rom").exists(),
        "the disc's reduction is kept"
    );
    assert!(!keep.join("pad.rom").exists());
    // Fixed: the disc is taken, not reduced (none of its stages runs); the pad is reduced.
    let (fixed, stages) = run(&good);
    let (model, report) = fixed.unwrap();
    assert!(report.parts[0].reused && !report.parts[1].reused);
    assert!(
        !stages.iter().any(|(p, s)| p == "disc" && *s != Stage::Read),
        "{stages:?}"
    );
    assert!(
        stages
            .iter()
            .any(|(p, s)| p == "pad" && *s == Stage::Eigensolve)
    );
    // The same model, bit for bit, as reduced from scratch.
    let (scratch, _) =
        reduce_brake_loaded(&good, coarse("disc"), vec![coarse("pad")], &mut |_, _| {}).unwrap();
    assert!(model == scratch, "the model with the kept disc differs");
    // Asked for other options, the kept disc no longer stands for it: reduced again.
    let other = BrakeInputs {
        modes: ModeChoice::Fixed(21),
        ..good
    };
    let (again, _) = run(&other);
    let (model, report) = again.unwrap();
    assert!(!report.parts[0].reused);
    assert_eq!(model.parts[0].info.fixed_interface_hz.len(), 21);
    forget_kept(&keep).unwrap();
    assert!(!keep.exists());
    let _ = std::fs::remove_dir_all(&dir);
}
