//! The reduced model is the same bits for any number of threads (a test binary of its own:
//! it sets faer's global parallelism, as `squeal reduce` does), with the two parts reduced
//! at the same time, the supernodal solves split over subtrees and the Sturm check beside the
//! Lanczos iteration.

mod common;

use common::{coarse, coarse_inputs};
use squeal_reduce::brake::reduce_brake_loaded;
use squeal_reduce::craig_bampton::Stage;
use squeal_reduce::rom::InterfaceKind;

#[test]
fn rom_bytes_do_not_depend_on_the_thread_count() {
    faer::set_global_parallelism(faer::Par::Seq);
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| {
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
