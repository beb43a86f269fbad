//! The reduced model is the same bits for any number of threads (a test binary of its own:
//! it sets faer's global parallelism, as `squeal reduce` does), with the two parts reduced
//! at the same time, the supernodal solves split over subtrees and the Sturm check beside the
//! Lanczos iteration.

use super::common;

use common::{coarse, coarse_inputs};
use squeal_reduce::brake::reduce_brake_loaded;
use squeal_reduce::craig_bampton::Stage;
use squeal_reduce::rom::InterfaceKind;

/// Runs `f` in a rayon pool of `threads` threads.
fn on_threads<T: Send>(threads: usize, f: impl FnOnce() -> T + Send) -> T {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap()
        .install(f)
}

#[test]
fn rom_bytes_do_not_depend_on_the_thread_count() {
    faer::set_global_parallelism(faer::Par::Seq);
    let run = |threads: usize| {
        on_threads(threads, || {
            // Inputs made inside the pool: their factorization parallelism is its size.
            let inputs = coarse_inputs(InterfaceKind::Patch);
            let mut stages = Vec::new();
            let (model, report) =
                reduce_brake_loaded(&inputs, coarse("disc"), vec![coarse("pad")], &mut |p, s| {
                    stages.push((p.to_string(), s))
                })
                .unwrap();
            for part in &report.parts {
                let r = &part.reduce;
                // The parallel pieces ran: subtree-parallel solves and the Sturm check beside
                // the Lanczos iteration.
                assert!(r.factor.solve_tasks > 1, "{}: serial solves", part.name);
                assert!(
                    r.eig.sturm_beside,
                    "{}: Sturm check after the iteration",
                    part.name
                );
            }
            (model.to_bytes().unwrap(), stages)
        })
    };
    let (one, stages_one) = run(1);
    let (two, stages_two) = run(2);
    let (three, stages_three) = run(3);
    assert!(one == two, "the .rom bytes differ between 1 and 2 threads");
    assert!(
        one == three,
        "the .rom bytes differ between 1 and 3 threads"
    );
    // The parts are reduced at the same time: the progress callback saw each part's stages
    // in order, interleaved in some way.
    for stages in [stages_one, stages_two, stages_three] {
        for part in ["disc", "pad"] {
            let seen: Vec<Stage> = stages
                .iter()
                .filter(|(p, _)| p == part)
                .map(|(_, s)| *s)
                .collect();
            assert_eq!(seen, Stage::ALL[1..7].to_vec(), "{part}");
        }
    }
}

#[test]
fn pistons_as_footprints_reduce_to_the_same_bits_for_any_thread_count() {
    // The coarse brake with the pad's pistons as two 40 mm footprints on its back face (the
    // footprint rows and the springs added to the factored stiffness).
    faer::set_global_parallelism(faer::Par::Seq);
    let pad = || {
        let mut pad = coarse("pad");
        common::add_footprints(&mut pad.mesh);
        pad
    };
    let run = |threads: usize| {
        on_threads(threads, || {
            let mut inputs = coarse_inputs(InterfaceKind::Patch);
            inputs.pads[0].part.piston_footprints = vec!["FOOT_1".into(), "FOOT_2".into()];
            let (model, _) =
                reduce_brake_loaded(&inputs, coarse("disc"), vec![pad()], &mut |_, _| {}).unwrap();
            assert_eq!(model.parts[1].size(), 27 + 2 + 50);
            let bytes = model.to_bytes().unwrap();
            // The file reads back as written, with its footprints recorded.
            let back = squeal_reduce::rom::ReducedModel::from_bytes(
                &bytes,
                std::path::Path::new("footprints.rom"),
            )
            .unwrap();
            assert_eq!(back.parts[1].info, model.parts[1].info);
            let build = back.parts[1].info.build.as_ref().unwrap();
            assert_eq!(build.piston_footprints, ["FOOT_1", "FOOT_2"]);
            assert_eq!(*build, inputs.record(&inputs.pads[0].part));
            bytes
        })
    };
    let (one, two) = (run(1), run(2));
    assert!(one == two, "the .rom bytes differ between 1 and 2 threads");
}
