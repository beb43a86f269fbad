//! ARPACK backend: dsaupd_/dseupd_ (Lehoucq, Sorensen & Yang, ARPACK Users'
//! Guide, SIAM 1998) in shift-invert mode 3 for K phi = lambda M phi:
//! OP = (K - sigma M)^-1 M, B = M, which = "LM" (the lambda nearest sigma).
//! Raw FFI to the Fortran symbols of the system library (Debian package
//! libarpack2-dev, 32-bit Fortran INTEGER; gfortran passes the lengths of
//! CHARACTER arguments as trailing size_t values).

use crate::EigError;
use crate::lanczos::ShiftInvert;
use crate::solver::RawModes;
use faer::{Col, ColRef, Mat};
use std::sync::Mutex;

/// ARPACK keeps state in Fortran SAVE variables between reverse-communication
/// calls: two solves at once in one process would corrupt each other, so
/// every solve holds this lock from the first dsaupd_ to dseupd_.
static ARPACK_LOCK: Mutex<()> = Mutex::new(());

#[link(name = "arpack")]
unsafe extern "C" {
    fn dsaupd_(
        ido: *mut i32,
        bmat: *const u8,
        n: *const i32,
        which: *const u8,
        nev: *const i32,
        tol: *const f64,
        resid: *mut f64,
        ncv: *const i32,
        v: *mut f64,
        ldv: *const i32,
        iparam: *mut i32,
        ipntr: *mut i32,
        workd: *mut f64,
        workl: *mut f64,
        lworkl: *const i32,
        info: *mut i32,
        bmat_len: usize,
        which_len: usize,
    );

    fn dseupd_(
        rvec: *const i32,
        howmny: *const u8,
        select: *mut i32,
        d: *mut f64,
        z: *mut f64,
        ldz: *const i32,
        sigma: *const f64,
        bmat: *const u8,
        n: *const i32,
        which: *const u8,
        nev: *const i32,
        tol: *const f64,
        resid: *mut f64,
        ncv: *const i32,
        v: *mut f64,
        ldv: *const i32,
        iparam: *mut i32,
        ipntr: *mut i32,
        workd: *mut f64,
        workl: *mut f64,
        lworkl: *const i32,
        info: *mut i32,
        howmny_len: usize,
        bmat_len: usize,
        which_len: usize,
    );
}

fn to_i32(x: usize, what: &str) -> Result<i32, EigError> {
    i32::try_from(x).map_err(|_| EigError::InvalidOption {
        what: format!("{what} = {x} exceeds ARPACK's 32-bit integers"),
    })
}

/// Copies `n` values of ARPACK's work array starting at the 1-based pointer `p`.
fn slice_at(workd: &[f64], p: i32, n: usize) -> Result<ColRef<'_, f64>, EigError> {
    let start = usize::try_from(p - 1).map_err(|_| EigError::Arpack {
        routine: "dsaupd",
        info: p,
    })?;
    let s = workd.get(start..start + n).ok_or(EigError::Arpack {
        routine: "dsaupd",
        info: p,
    })?;
    Ok(ColRef::from_slice(s))
}

fn write_at(workd: &mut [f64], p: i32, y: &Col<f64>) -> Result<(), EigError> {
    let n = y.nrows();
    let start = usize::try_from(p - 1).map_err(|_| EigError::Arpack {
        routine: "dsaupd",
        info: p,
    })?;
    let s = workd.get_mut(start..start + n).ok_or(EigError::Arpack {
        routine: "dsaupd",
        info: p,
    })?;
    for (o, v) in s.iter_mut().zip(y.iter()) {
        *o = *v;
    }
    Ok(())
}

/// The `nev` eigenpairs nearest above `sigma` by ARPACK mode 3, with the
/// (possibly deflated) shift-invert operator `op`.
pub(crate) fn shift_invert(
    op: &ShiftInvert<'_>,
    nev: usize,
    ncv: usize,
    sigma: f64,
    tol: f64,
    max_iter: usize,
) -> Result<RawModes, EigError> {
    let n = op.n();
    if !(nev < ncv && ncv <= n) {
        return Err(EigError::TooManyRequested {
            requested: nev,
            available: n.saturating_sub(1).min(ncv.saturating_sub(1)),
        });
    }
    let (n32, nev32, ncv32) = (to_i32(n, "n")?, to_i32(nev, "nev")?, to_i32(ncv, "ncv")?);
    let lworkl = to_i32(ncv * (ncv + 8), "lworkl")?;
    let mut resid = vec![0.0; n];
    let mut v = vec![0.0; n * ncv];
    let mut workd = vec![0.0; 3 * n];
    let mut workl = vec![0.0; ncv * (ncv + 8)];
    let mut iparam = [0i32; 11];
    iparam[0] = 1; // exact shifts
    iparam[2] = to_i32(max_iter, "max_iter")?;
    iparam[6] = 3; // mode 3: shift-invert
    let mut ipntr = [0i32; 11];
    let mut ido = 0i32;
    let mut info = 0i32; // ARPACK's own (deterministic) random start vector
    let (bmat, which) = (b"G", b"LM");
    let mut applications = 0usize;
    // A poisoned lock only means another solve panicked; ARPACK restarts from ido = 0.
    let _guard = ARPACK_LOCK.lock().unwrap_or_else(|e| e.into_inner());
    loop {
        // SAFETY: all arrays have the sizes dsaupd documents for these n, nev, ncv, lworkl.
        unsafe {
            dsaupd_(
                &mut ido,
                bmat.as_ptr(),
                &n32,
                which.as_ptr(),
                &nev32,
                &tol,
                resid.as_mut_ptr(),
                &ncv32,
                v.as_mut_ptr(),
                &n32,
                iparam.as_mut_ptr(),
                ipntr.as_mut_ptr(),
                workd.as_mut_ptr(),
                workl.as_mut_ptr(),
                &lworkl,
                &mut info,
                1,
                2,
            );
        }
        match ido {
            -1 => {
                let mx = op.mass(slice_at(&workd, ipntr[0], n)?);
                let y = op.solve(mx.as_ref())?;
                applications += 1;
                write_at(&mut workd, ipntr[1], &y)?;
            }
            1 => {
                let y = op.solve(slice_at(&workd, ipntr[2], n)?)?;
                applications += 1;
                write_at(&mut workd, ipntr[1], &y)?;
            }
            2 => {
                let mx = op.mass(slice_at(&workd, ipntr[0], n)?);
                write_at(&mut workd, ipntr[1], &mx)?;
            }
            _ => break,
        }
    }
    let iterations = usize::try_from(iparam[2]).unwrap_or(0);
    if info == 1 {
        let converged = usize::try_from(iparam[4]).unwrap_or(0);
        return Err(EigError::NotConverged {
            converged,
            requested: nev,
            iterations,
            residuals: Vec::new(),
            worst: f64::NAN,
        });
    }
    if info != 0 {
        return Err(EigError::Arpack {
            routine: "dsaupd",
            info,
        });
    }
    let rvec = 1i32;
    let mut select = vec![0i32; ncv];
    let mut d = vec![0.0; nev];
    let mut z = vec![0.0; n * nev];
    // SAFETY: as above; z is n x nev, select has ncv entries.
    unsafe {
        dseupd_(
            &rvec,
            b"A".as_ptr(),
            select.as_mut_ptr(),
            d.as_mut_ptr(),
            z.as_mut_ptr(),
            &n32,
            &sigma,
            bmat.as_ptr(),
            &n32,
            which.as_ptr(),
            &nev32,
            &tol,
            resid.as_mut_ptr(),
            &ncv32,
            v.as_mut_ptr(),
            &n32,
            iparam.as_mut_ptr(),
            ipntr.as_mut_ptr(),
            workd.as_mut_ptr(),
            workl.as_mut_ptr(),
            &lworkl,
            &mut info,
            1,
            1,
            2,
        );
    }
    if info != 0 {
        return Err(EigError::Arpack {
            routine: "dseupd",
            info,
        });
    }
    let nconv = usize::try_from(iparam[4]).unwrap_or(0);
    if nconv < nev {
        return Err(EigError::NotConverged {
            converged: nconv,
            requested: nev,
            iterations,
            residuals: Vec::new(),
            worst: f64::NAN,
        });
    }
    let vectors = Mat::from_fn(n, nev, |i, j| z[j * n + i]);
    Ok(RawModes {
        values: d,
        vectors,
        iterations,
        applications,
        block: 1,
    })
}
