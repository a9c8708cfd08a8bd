//! `--max-memory` and `--time-limit`, shared by the commands that solve: how much of the machine
//! one run may take (docs/cli.md, "Limits").

use clap::Args;

use crate::pipeline::machine::default_max_memory;

#[derive(Args, Debug, Clone, Default)]
pub struct LimitArgs {
    /// Refuse (exit 2, before allocating) a scene whose solve is estimated to need more memory
    /// than this, bytes, with an optional suffix K, M, G or T (powers of 1024)
    /// [default: half of the smallest of physical memory, cgroup limit and RLIMIT_AS/DATA;
    /// 4G where none can be read].
    #[arg(long, value_name = "BYTES", value_parser = parse_bytes)]
    pub max_memory: Option<u64>,
    /// Stop each solve after this many seconds, writing its last iterate with
    /// "converged": false, "stopped": "time limit" (overrides the scene's solver.time_limit).
    #[arg(long, value_name = "SECONDS", value_parser = parse_seconds)]
    pub time_limit: Option<f64>,
}

impl LimitArgs {
    /// The limits these options ask for, passed down to every solve of the command.
    pub fn values(&self) -> crate::pipeline::Limits {
        crate::pipeline::Limits {
            memory: self.max_memory.unwrap_or_else(default_max_memory),
            time: self.time_limit,
        }
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pipeline::machine::*;

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

    /// The default takes half of the smallest of physical memory, cgroup and rlimit limits;
    /// "max", "unlimited" and v1's page-rounded 2⁶³ mean no limit.
    #[test]
    fn the_default_limit_is_half_the_smallest_of_machine_cgroup_and_rlimit() {
        let meminfo = "MemTotal:       16384000 kB\nMemFree:         1000 kB\n";
        let physical = parse_meminfo(meminfo);
        assert_eq!(physical, Some(16_384_000 * 1024));
        assert_eq!(parse_cgroup_limit("max\n"), None);
        assert_eq!(parse_cgroup_limit("9223372036854771712\n"), None);
        assert_eq!(parse_cgroup_limit("6442450944\n"), Some(6 << 30));
        let limits =
            "Limit                     Soft Limit           Hard Limit           Units     \n\
            Max data size             unlimited            unlimited            bytes     \n\
            Max stack size            8388608              unlimited            bytes     \n\
            Max address space         4294967296           unlimited            bytes     \n";
        assert_eq!(parse_rlimits(limits), Some(4 << 30));
        let unlimited = limits.replace("4294967296", "unlimited");
        assert_eq!(parse_rlimits(&unlimited), None);
        // A 6 GiB cgroup on a 16 GB machine: 3 GiB, not 8 GB.
        assert_eq!(combined_default(physical, Some(6 << 30), None), 3 << 30);
        assert_eq!(
            combined_default(physical, Some(6 << 30), Some(4 << 30)),
            2 << 30
        );
        assert_eq!(
            combined_default(physical, None, None),
            16_384_000 * 1024 / 2
        );
        assert_eq!(combined_default(None, None, None), FALLBACK_MAX_MEMORY);
        let files = cgroup_files(Some("12:memory:/user/job7\n0::/user.slice/job7\n"));
        assert!(files.contains(&"/sys/fs/cgroup/memory/user/job7/memory.limit_in_bytes".into()));
        assert!(files.contains(&"/sys/fs/cgroup/user.slice/job7/memory.max".into()));
    }
}
