//! MatrixMarket export of a reduced model, for MATLAB and Python users.
//!
//! Each part's reduced stiffness and mass (eqs 6–7) go to `<stem>_<part>_K.mtx` and
//! `<stem>_<part>_M.mtx` (dense `array real general`, column-major as the format requires), and
//! `<stem>_<part>_dofs.csv` says what each row is. The names and the `direction` column follow
//! `squeal fe export` (`<stem>_K.mtx`, `<stem>_dofs.csv`, direction 1 = x, 2 = y, 3 = z), so a
//! script written for one reads the other.

use crate::rom::{DofLabel, ReducedModel, ReducedPart, RomError};
use std::io::Write;
use std::path::{Path, PathBuf};

/// Writes the three files of every part of `model` into `dir`, each atomically, and returns
/// their paths in the order written.
///
/// `<stem>_<part>_dofs.csv` has one line per reduced dof: `dof` (1-based, the row of the
/// matrices), `kind` (`contact`, `piston` or `mode`), `point` or `mode` (1-based), `direction`
/// (1, 2, 3 for x, y, z; 0 when the dof moves along another unit vector), that unit vector
/// `dx, dy, dz`, and the point's coordinates `x, y, z`.
pub fn write_matrix_market(
    model: &ReducedModel,
    dir: &Path,
    stem: &str,
) -> Result<Vec<PathBuf>, RomError> {
    let mut written = Vec::new();
    for part in &model.parts {
        let base = format!("{stem}_{}", part.info.name);
        for (what, eq, mat) in [("K", 6, &part.k), ("M", 7, &part.m)] {
            let path = dir.join(format!("{base}_{what}.mtx"));
            let n = mat.nrows();
            let values: Vec<f64> = (0..n * n).map(|k| mat[(k % n, k / n)]).collect();
            let comment = format!(
                "squeal reduced {what} of part {} (eq {eq}); row i is described by line i of {base}_dofs.csv",
                part.info.name
            );
            squeal_io::mtx::write_dense(&path, n, n, &values, &comment)?;
            written.push(path);
        }
        let path = dir.join(format!("{base}_dofs.csv"));
        squeal_io::atomic_write(&path, |w| write_dof_labels(w, part))?;
        written.push(path);
    }
    Ok(written)
}

/// The lines of `<stem>_<part>_dofs.csv` (see [`write_matrix_market`]).
fn write_dof_labels(w: &mut dyn Write, part: &ReducedPart) -> std::io::Result<()> {
    writeln!(w, "dof,kind,point,mode,direction,dx,dy,dz,x,y,z")?;
    for (i, label) in part.info.dofs.iter().enumerate() {
        let row = i + 1;
        let (point, direction) = match *label {
            DofLabel::Mode { mode } => {
                writeln!(w, "{row},mode,,{},,,,,,,", mode + 1)?;
                continue;
            }
            DofLabel::Point { point, direction } => {
                let mut d = [0.0; 3];
                if let Some(x) = d.get_mut(usize::from(direction)) {
                    *x = 1.0;
                }
                (point, d)
            }
            DofLabel::Along { point, direction } => (point, direction),
            // A coupling point's rotation about a coordinate axis (rad): kind `rotation`.
            DofLabel::Rotation { point, axis } => {
                let mut d = [0.0; 3];
                if let Some(x) = d.get_mut(usize::from(axis)) {
                    *x = 1.0;
                }
                let at = part.info.points.get(point).map_or([0.0; 3], |p| p.position);
                writeln!(
                    w,
                    "{row},rotation,{},,{},{},{},{},{:e},{:e},{:e}",
                    point + 1,
                    axis + 1,
                    d[0],
                    d[1],
                    d[2],
                    at[0],
                    at[1],
                    at[2]
                )?;
                continue;
            }
        };
        let Some(p) = part.info.points.get(point) else {
            return Err(std::io::Error::other(format!(
                "dof {row} names interface point {point}, but the part has {}",
                part.info.points.len()
            )));
        };
        let role = match p.role {
            crate::rom::PointRole::Contact => "contact",
            crate::rom::PointRole::Piston => "piston",
            crate::rom::PointRole::Face => "face",
            crate::rom::PointRole::Coupling => "coupling",
            crate::rom::PointRole::Tie => "tie",
        };
        let axis = direction
            .iter()
            .position(|&c| c == 1.0)
            .filter(|_| direction.iter().filter(|&&c| c == 0.0).count() == 2)
            .map_or(0, |k| k + 1);
        let [dx, dy, dz] = direction;
        let [x, y, z] = p.position;
        writeln!(
            w,
            "{row},{role},{},,{axis},{dx},{dy},{dz},{x:e},{y:e},{z:e}",
            point + 1
        )?;
    }
    Ok(())
}
