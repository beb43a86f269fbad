//! Factorization and 50 fixed-interface modes of the bundled brake meshes
//! (tet10, assembled by squeal-fe), printing a table. One configuration per
//! process so that the peak memory (VmHWM) is that configuration's:
//!
//! ```text
//! nice cargo bench -p squeal-reduce --bench eigs_brake -- --mesh=disc
//! nice cargo bench -p squeal-reduce --bench eigs_brake -- --mesh=pad
//! nice cargo bench -p squeal-reduce --bench eigs_brake -- --mesh=disc --ordering=amd --block=1
//! options: --mesh=disc|pad|PATH.inp  --level=fine|medium|coarse  --nev=N (50)
//!          --ordering=nd|amd  --block=B (8; 1 = single-vector Lanczos)  --ncv=N
//!          --no-sturm  --no-table (skip the multi-RHS solve table)  --no-eig
//!          --slice=S (at most S new pairs per shift; 0: one shift)
//! threads: RAYON_NUM_THREADS=1 (faer's parallelism follows rayon's pool)
//! ```
//!
//! `--ordering=amd --block=1` runs the algorithms the crate had before
//! nested dissection and the block method (AMD, single-vector Lanczos, the
//! Sturm LBL^T on the AMD ordering).
//!
//! The disc is clamped on `CLAMP`; the pad is held as its interior problem in
//! the Craig-Bampton reduction: `ABUTMENT` in x and y, `PISTON` and `CONTACT`
//! nodes in all directions.

use squeal_eigs::{
    CholeskyOptions, EigOptions, FillOrdering, SparseCholesky, lowest_modes_with_factor,
};
use squeal_fe::{DofMap, MaterialTable, Restraint, assemble};
use std::path::PathBuf;
use std::time::Instant;

// The printing helpers of the squeal-eigs benchmarks, shared as a file.
#[path = "../../squeal-eigs/benches/common/mod.rs"]
mod common;

fn arg<'a>(args: &'a [String], key: &str) -> Option<&'a str> {
    args.iter().find_map(|a| a.strip_prefix(key))
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let which = arg(&args, "--mesh=").unwrap_or("disc");
    let level = arg(&args, "--level=").unwrap_or("fine");
    let nev: usize = arg(&args, "--nev=")
        .and_then(|x| x.parse().ok())
        .unwrap_or(50);
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../meshes");
    let (path, restraints) = match which {
        "disc" => (
            root.join(format!("disc_{level}.inp")),
            vec![Restraint::clamp("CLAMP")],
        ),
        "pad" => (
            root.join(format!("pad_{level}.inp")),
            vec![
                Restraint::set("ABUTMENT", [true, true, false]),
                Restraint::clamp("PISTON"),
                Restraint::clamp("CONTACT"),
            ],
        ),
        other => (PathBuf::from(other), vec![Restraint::clamp("CLAMP")]),
    };
    let t = Instant::now();
    let mesh = squeal_mesh::read(&path).expect("mesh").mesh;
    let materials = MaterialTable::from_mesh(&mesh, &[]).expect("materials");
    let dofs = DofMap::new(&mesh, &restraints).expect("dof map");
    let sys = assemble(&mesh, &materials, &dofs).expect("assembly");
    let assemble_time = t.elapsed();
    let n = sys.k.nrows();
    println!(
        "# squeal-eigs brake bench: {}, n = {n}, nnz(K) = {}, nev = {nev}",
        path.display(),
        sys.k.compute_nnz()
    );
    println!("# threads: {}", rayon::current_num_threads());
    println!(
        "read + assemble (s)     {:8.2}",
        assemble_time.as_secs_f64()
    );
    let ordering = match arg(&args, "--ordering=") {
        Some("amd") => FillOrdering::Amd,
        _ => FillOrdering::NestedDissection,
    };
    println!("# ordering: {ordering:?}");
    let copts = {
        let mut o = CholeskyOptions::default();
        o.ordering = ordering;
        o
    };
    let t = Instant::now();
    let f = SparseCholesky::factorize_with(sys.k.as_ref(), &copts).expect("factorization");
    let total_factor = t.elapsed();
    common::print_factor(&f.stats(), total_factor);
    let table: &[usize] = if args.iter().any(|a| a == "--no-table") {
        &[]
    } else {
        &[1, 4, 8, 16, 32, 64]
    };
    println!("solve time per right-hand side (ms), by columns solved at once:");
    for &cols in table {
        let reps = (64 / cols).clamp(2, 8);
        let t = Instant::now();
        for _ in 0..reps {
            let x = f
                .solve(faer::Mat::<f64>::ones(n, cols).as_ref())
                .expect("solve");
            drop(x);
        }
        let per = t.elapsed().as_secs_f64() * 1000.0 / (reps * cols) as f64;
        println!("  {cols:>3} columns           {per:8.2}");
    }
    if args.iter().any(|a| a == "--no-eig") {
        println!("peak memory VmHWM (MiB) {:8.1}", common::peak_mib());
        return;
    }
    let defaults = EigOptions::default();
    let opts = {
        let mut o = defaults;
        o.block_size = arg(&args, "--block=")
            .and_then(|x| x.parse().ok())
            .unwrap_or(defaults.block_size);
        o.ncv = arg(&args, "--ncv=").and_then(|x| x.parse().ok());
        o.sturm_check = !args.iter().any(|a| a == "--no-sturm");
        o.slice = arg(&args, "--slice=")
            .and_then(|x| x.parse().ok())
            .unwrap_or(defaults.slice);
        o
    };
    let t = Instant::now();
    let modes = lowest_modes_with_factor(sys.k.as_ref(), sys.m.as_ref(), &f, nev, &opts)
        .expect("eigensolve");
    let total = t.elapsed();
    let st = modes.stats;
    println!("eigensolve total (s)    {:8.2}", total.as_secs_f64());
    let iteration = match st.sturm_beside {
        true => st.solve_time,
        false => st.solve_time.saturating_sub(st.sturm_time),
    };
    println!("  iteration (s)         {:8.2}", iteration.as_secs_f64());
    println!(
        "    of which solves (s) {:8.2}",
        st.operator_time.as_secs_f64()
    );
    println!("    M products (s)      {:8.2}", st.mass_time.as_secs_f64());
    println!("    Ritz, restarts (s)  {:8.2}", st.ritz_time.as_secs_f64());
    println!(
        "  Sturm check (s)       {:8.2}{}",
        st.sturm_time.as_secs_f64(),
        if st.sturm_beside {
            " (beside the iteration)"
        } else {
            ""
        }
    );
    println!(
        "  iterations / rounds   {:>5} / {}",
        st.iterations, st.rounds
    );
    println!("  OP applications       {:>8}", st.operator_applications);
    println!("  shifts                {:>8}", st.shifts);
    println!("  block / ncv           {:>5} / {}", st.block, st.ncv);
    println!(
        "  f_1 / f_{nev} (Hz)         {:.3} / {:.3}",
        modes.values[0].sqrt() / std::f64::consts::TAU,
        modes.values[nev - 1].sqrt() / std::f64::consts::TAU
    );
    println!(
        "  worst backward error  {:.2e}",
        modes.residuals.iter().copied().fold(0.0, f64::max)
    );
    println!("peak memory VmHWM (MiB) {:8.1}", common::peak_mib());
}
