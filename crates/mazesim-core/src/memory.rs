//! How much more memory this process may allocate, as far as the system tells: what a batch's
//! size is checked against before it is allocated.

/// The least of the address space left under the process's limit (`RLIMIT_AS`, from
/// `/proc/self/limits` and `/proc/self/status`) and the memory the system has available
/// (`MemAvailable` plus free swap, from `/proc/meminfo`); `None` where neither is known.
pub fn allocatable_bytes() -> Option<u64> {
    let address_space = address_space_limit()
        .zip(kib_field("/proc/self/status", "VmSize:"))
        .map(|(limit, used)| limit.saturating_sub(used));
    let available = kib_field("/proc/meminfo", "MemAvailable:")
        .map(|m| m + kib_field("/proc/meminfo", "SwapFree:").unwrap_or(0));
    match (address_space, available) {
        (Some(a), Some(b)) => Some(a.min(b)),
        (a, b) => a.or(b),
    }
}

/// The soft address-space limit in bytes, `None` when unlimited or unknown.
fn address_space_limit() -> Option<u64> {
    let limits = std::fs::read_to_string("/proc/self/limits").ok()?;
    let line = limits
        .lines()
        .find(|l| l.starts_with("Max address space"))?;
    line["Max address space".len()..]
        .split_whitespace()
        .next()?
        .parse()
        .ok()
}

/// A `kB` field of a `/proc` file, in bytes.
fn kib_field(path: &str, name: &str) -> Option<u64> {
    let text = std::fs::read_to_string(path).ok()?;
    let line = text.lines().find(|l| l.starts_with(name))?;
    let kib: u64 = line[name.len()..].split_whitespace().next()?.parse().ok()?;
    Some(kib.saturating_mul(1024))
}

#[cfg(test)]
mod tests {
    #[test]
    fn a_linux_system_tells_its_memory() {
        if std::path::Path::new("/proc/meminfo").exists() {
            let free = super::allocatable_bytes().expect("known on Linux");
            assert!(free > 1 << 20, "{free}");
        }
    }
}
