//! Memory: what a sparse reduction will need, what the machine has, what the process used.

use crate::error::LinalgError;
/// Bytes a sparse Craig–Bampton reduction of a trilinear-brick solid with `dofs` DOF needs,
/// estimated before anything is allocated: $K$ and $K_{ii}$ (~81 entries per row, 16 bytes
/// each), the Cholesky factor and the Lanczos basis (three n × 64 blocks).
///
/// The factor's fill under the eigensolvers' nested-dissection ordering, from faer's symbolic
/// analysis of the refined slab (`examples/substructure_tree.rs`): 844, 1 052, 1 533 and 2 163
/// entries per DOF at 90 768, 153 957, 401 778 and 992 565 DOF (280 at 6 825), i.e. growing as
/// about $n^{0.4}$; the estimate takes $844\,(n / 90\,768)^{0.4}$ with a tenth to spare (1.09 to
/// 1.18 times the measured fill at those sizes).
pub fn estimated_reduction_bytes(dofs: usize) -> u64 {
    let n = dofs as f64;
    let stiffness = 2.0 * 16.0 * 81.0 * n;
    let factor = 8.0 * 1.1 * 844.0 * n * (n / 90_768.0).powf(0.4);
    let lanczos = 3.0 * 8.0 * 64.0 * n;
    (stiffness + factor + lanczos) as u64
}

/// Refuses, before anything is allocated, a `dofs`-DOF sparse reduction whose
/// [estimate](estimated_reduction_bytes) exceeds the memory the machine has free
/// (`LinalgError::MeshTooLarge`); returns the estimate otherwise.
pub fn check_reduction_memory(dofs: usize) -> crate::linalg::Result<u64> {
    let needed = estimated_reduction_bytes(dofs);
    if let Some(available) = available_bytes()
        && needed > available
    {
        return Err(LinalgError::MeshTooLarge {
            dofs,
            estimated_gb: needed as f64 / 1e9,
            available_gb: available as f64 / 1e9,
        });
    }
    Ok(needed)
}

/// Refuses a sparse factor of `entries` values (8 bytes each) and `workspace` bytes of
/// scratch when they exceed `available` bytes ([`available_bytes`]; no check where the
/// system does not say), with [`LinalgError::FactorTooLarge`] naming `what` and `matrix`.
pub(crate) fn check_factor_memory(
    what: &'static str,
    matrix: &crate::error::MatrixLabel,
    entries: usize,
    workspace: usize,
    available: Option<u64>,
) -> crate::linalg::Result<()> {
    let needed = 8.0 * entries as f64 + workspace as f64;
    match available {
        Some(free) if needed > free as f64 => Err(LinalgError::FactorTooLarge {
            what,
            matrix: matrix.clone(),
            entries,
            needed_gb: needed / 1e9,
            available_gb: free as f64 / 1e9,
        }),
        _ => Ok(()),
    }
}

/// `MemAvailable` of `/proc/meminfo`, bytes (None where it cannot be read).
pub fn available_bytes() -> Option<u64> {
    proc_kib("/proc/meminfo", "MemAvailable:")
}

/// The process's resident set now (`VmRSS` of `/proc/self/status`), bytes.
pub fn resident_bytes() -> Option<u64> {
    proc_kib("/proc/self/status", "VmRSS:")
}

/// The process's peak resident set (`VmHWM` of `/proc/self/status`), bytes.
pub fn peak_resident_bytes() -> Option<u64> {
    proc_kib("/proc/self/status", "VmHWM:")
}

fn proc_kib(file: &str, key: &str) -> Option<u64> {
    let text = std::fs::read_to_string(file).ok()?;
    let line = text.lines().find(|l| l.starts_with(key))?;
    let kib: u64 = line[key.len()..]
        .trim()
        .trim_end_matches("kB")
        .trim()
        .parse()
        .ok()?;
    Some(kib * 1024)
}

/// Resets the process's peak resident set to its current size (writes `5` to
/// `/proc/self/clear_refs`, Linux), so that [`peak_resident_bytes`] afterwards measures one
/// phase; false where the kernel does not allow it (the peak then stays the process's).
pub fn reset_peak_resident() -> bool {
    std::fs::write("/proc/self/clear_refs", "5").is_ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[cfg(target_os = "linux")]
    #[test]
    fn the_resident_set_is_read_and_never_above_its_peak() {
        let now = resident_bytes().expect("VmRSS in /proc/self/status");
        let peak = peak_resident_bytes().expect("VmHWM in /proc/self/status");
        // A test process holds at least its own code: over a megabyte.
        assert!(now > 1 << 20, "{now}");
        assert!(now <= peak, "resident {now} above peak {peak}");
    }

    /// A factor is refused when its values and workspace exceed what is free, with the
    /// numbers in the message; it passes when they fit or when the system does not say.
    #[test]
    fn a_factor_larger_than_the_free_memory_is_refused_naming_its_size() {
        let label = crate::error::MatrixLabel::from("interior stiffness K_ii");
        // 2.481e9 entries: faer's factor of the 1 M-DOF slab under nested dissection.
        let entries = 2_481_000_000usize;
        let err = check_factor_memory(
            "Cholesky factor",
            &label,
            entries,
            1 << 30,
            Some(20e9 as u64),
        )
        .unwrap_err();
        let text = err.to_string();
        assert!(
            text.contains("Cholesky factor of the interior stiffness K_ii matrix")
                && text.contains("needs 20.92 GB (2481000000 entries")
                && text.contains("20.00 GB this machine has free"),
            "{text}"
        );
        assert!(
            check_factor_memory("Cholesky factor", &label, entries, 0, Some(21e9 as u64)).is_ok()
        );
        assert!(check_factor_memory("Cholesky factor", &label, entries, 0, None).is_ok());
    }
}
