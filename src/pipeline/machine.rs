//! How much memory this process may take: the machine's, its cgroup's and its rlimits' limits,
//! read from /proc and /sys (the default of `--max-memory` and of Python's solves).

/// The fraction of physical memory a run may take by default: the machine is shared, and
/// the estimate is within a factor of two of the measured peak (docs/performance.md).
pub const DEFAULT_MEMORY_FRACTION: f64 = 0.5;
/// Default `--max-memory` where physical memory cannot be read (not Linux).
pub const FALLBACK_MAX_MEMORY: u64 = 4 << 30;

/// Half of the memory this process may take: the smallest of the physical memory (`MemTotal`
/// in /proc/meminfo), the cgroup's limit (v2 `memory.max`, v1 `memory.limit_in_bytes`) and
/// the process's RLIMIT_AS and RLIMIT_DATA (/proc/self/limits); [`FALLBACK_MAX_MEMORY`] where
/// none can be read. Past a cgroup's or rlimit's limit the process is killed or its
/// allocation aborts, which a refusal with exit 2 must come before.
pub fn default_max_memory() -> u64 {
    let read = |p: &str| std::fs::read_to_string(p).ok();
    let physical = read("/proc/meminfo").and_then(|t| parse_meminfo(&t));
    let cgroup = cgroup_files(read("/proc/self/cgroup").as_deref())
        .iter()
        .filter_map(|p| read(p).and_then(|t| parse_cgroup_limit(&t)))
        .min();
    let rlimit = read("/proc/self/limits").and_then(|t| parse_rlimits(&t));
    combined_default(physical, cgroup, rlimit)
}

/// [`DEFAULT_MEMORY_FRACTION`] of the smallest of the limits that are known.
pub fn combined_default(physical: Option<u64>, cgroup: Option<u64>, rlimit: Option<u64>) -> u64 {
    [physical, cgroup, rlimit]
        .into_iter()
        .flatten()
        .min()
        .map_or(FALLBACK_MAX_MEMORY, |m| {
            ((m as f64 * DEFAULT_MEMORY_FRACTION) as u64).max(1)
        })
}

/// `MemTotal` of /proc/meminfo, bytes.
pub fn parse_meminfo(text: &str) -> Option<u64> {
    let line = text.lines().find(|l| l.starts_with("MemTotal:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    kib.checked_mul(1024)
}

/// A cgroup memory limit file's value: v2 `memory.max` ("max": none) or v1
/// `memory.limit_in_bytes` (a value near 2⁶³, rounded to pages, means none).
pub fn parse_cgroup_limit(text: &str) -> Option<u64> {
    let t = text.trim();
    if t == "max" {
        return None;
    }
    t.parse::<u64>().ok().filter(|&b| b > 0 && b < 1 << 62)
}

/// The smaller soft limit of "Max address space" and "Max data size" in /proc/self/limits,
/// bytes ("unlimited": none).
pub fn parse_rlimits(text: &str) -> Option<u64> {
    text.lines()
        .filter_map(|l| {
            let rest = l
                .strip_prefix("Max address space")
                .or_else(|| l.strip_prefix("Max data size"))?;
            rest.split_whitespace().next()?.parse::<u64>().ok()
        })
        .min()
}

/// The memory limit files that may hold this process: its own cgroup's (from /proc/self/cgroup,
/// v2 `0::PATH` and v1 `N:memory:PATH`) and the mount's root (a container's own limit where
/// the namespace hides the path).
pub fn cgroup_files(proc_self_cgroup: Option<&str>) -> Vec<String> {
    let mut files = vec![
        "/sys/fs/cgroup/memory.max".to_string(),
        "/sys/fs/cgroup/memory/memory.limit_in_bytes".to_string(),
    ];
    for line in proc_self_cgroup.unwrap_or("").lines() {
        let mut parts = line.splitn(3, ':');
        let (Some(id), Some(controllers), Some(path)) = (parts.next(), parts.next(), parts.next())
        else {
            continue;
        };
        let path = path.trim().trim_end_matches('/');
        if path.is_empty() || path.contains("..") {
            continue;
        }
        if id == "0" && controllers.is_empty() {
            files.push(format!("/sys/fs/cgroup{path}/memory.max"));
        } else if controllers.split(',').any(|c| c == "memory") {
            files.push(format!("/sys/fs/cgroup/memory{path}/memory.limit_in_bytes"));
        }
    }
    files
}
