//! `--max-memory` and `--time-limit`, shared by the commands that solve: how much of the machine
//! one run may take (docs/cli.md, "Limits").

use clap::Args;

/// The fraction of physical memory a run may take by default: the machine is shared, and
/// the estimate is within a factor of two of the measured peak (docs/performance.md).
pub const DEFAULT_MEMORY_FRACTION: f64 = 0.5;
/// Default `--max-memory` where physical memory cannot be read (not Linux).
pub const FALLBACK_MAX_MEMORY: u64 = 4 << 30;

#[derive(Args, Debug, Clone, Default)]
pub struct LimitArgs {
    /// Refuse (exit 2, before allocating) a scene whose solve is estimated to need more memory
    /// than this, bytes, with an optional suffix K, M, G or T (powers of 1024)
    /// [default: half of the physical memory; 4G where it cannot be read].
    #[arg(long, value_name = "BYTES", value_parser = parse_bytes)]
    pub max_memory: Option<u64>,
    /// Stop each solve after this many seconds, writing its last iterate with
    /// "converged": false, "stopped": "time limit" (overrides the scene's solver.time_limit).
    #[arg(long, value_name = "SECONDS", value_parser = parse_seconds)]
    pub time_limit: Option<f64>,
}

impl LimitArgs {
    /// Makes the limits hold for every solve of this process.
    pub fn apply(&self) {
        crate::pipeline::set_memory_limit(self.max_memory.unwrap_or_else(default_max_memory));
        crate::pipeline::set_time_limit(self.time_limit);
    }
}

/// A byte count with an optional binary suffix: 1000, 512K, 512M, 4G, 1.5G, 1T (case-insensitive,
/// an optional trailing B or iB).
pub fn parse_bytes(s: &str) -> Result<u64, String> {
    let t = s.trim();
    let lower = t.to_ascii_lowercase();
    let body = lower
        .strip_suffix("ib")
        .or_else(|| lower.strip_suffix('b'))
        .unwrap_or(&lower);
    let (num, shift) = match body.chars().last() {
        Some('k') => (&body[..body.len() - 1], 10),
        Some('m') => (&body[..body.len() - 1], 20),
        Some('g') => (&body[..body.len() - 1], 30),
        Some('t') => (&body[..body.len() - 1], 40),
        _ => (body, 0),
    };
    let v: f64 = num
        .trim()
        .parse()
        .map_err(|_| format!("expected a byte count such as 4G, 512M or 1000000, got {s:?}"))?;
    let bytes = v * (1u64 << shift) as f64;
    if !(bytes.is_finite() && bytes >= 1.0 && bytes < u64::MAX as f64) {
        return Err(format!(
            "must be a positive byte count below 16 EiB, got {s:?}"
        ));
    }
    Ok(bytes as u64)
}

fn parse_seconds(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(t) if t.is_finite() && t > 0.0 => Ok(t),
        _ => Err(format!("must be a positive number of seconds, got {s:?}")),
    }
}

/// Half of the physical memory (`MemTotal` in /proc/meminfo), or [`FALLBACK_MAX_MEMORY`].
pub fn default_max_memory() -> u64 {
    physical_memory().map_or(FALLBACK_MAX_MEMORY, |m| {
        (m as f64 * DEFAULT_MEMORY_FRACTION) as u64
    })
}

fn physical_memory() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemTotal:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    kib.checked_mul(1024)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn byte_counts_take_binary_suffixes() {
        assert_eq!(parse_bytes("1000"), Ok(1000));
        assert_eq!(parse_bytes("512M"), Ok(512 << 20));
        assert_eq!(parse_bytes("4G"), Ok(4 << 30));
        assert_eq!(parse_bytes("4gib"), Ok(4 << 30));
        assert_eq!(parse_bytes("1.5k"), Ok(1536));
        assert_eq!(parse_bytes("2T"), Ok(2 << 40));
        for bad in ["", "G", "-1G", "0", "1e30T", "four", "nanG"] {
            assert!(parse_bytes(bad).is_err(), "{bad}");
        }
        assert!(default_max_memory() > 0);
    }
}
