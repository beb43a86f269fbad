//! The reduced model is the same bits for any number of threads (a test binary of its own:
//! it sets faer's global parallelism, as `squeal reduce` does).

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
            let (model, _) =
                reduce_brake_loaded(&inputs, coarse("disc"), coarse("pad"), &mut |p, s| {
                    stages.push((p.to_string(), s))
                })
                .unwrap();
            (model.to_bytes().unwrap(), stages)
        })
    };
    let (one, stages) = run(1);
    let (two, _) = run(2);
    assert!(one == two, "the .rom bytes differ between 1 and 2 threads");
    // The progress callback saw the disc's stages, then the pad's, in order.
    let expected: Vec<(String, Stage)> = ["disc", "pad"]
        .iter()
        .flat_map(|p| Stage::ALL[1..7].iter().map(move |s| (p.to_string(), *s)))
        .collect();
    assert_eq!(stages, expected);
}
