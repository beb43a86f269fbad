//! Who is writing: the host name, the running kernel (its boot id) and the PID namespace of
//! this process, and whether a process of the same kernel and namespace is alive.
//!
//! A process id alone names a process only within one PID namespace of one running kernel:
//! on a folder shared by several machines (NFS under Slurm) or by containers, pid 4242 of
//! another machine says nothing about pid 4242 here. Every file that names a process (the
//! temporary files of [`crate::atomic_write`], the lock of [`crate::folder`]) therefore also
//! carries this identity, and a process is judged dead only when the identity is this
//! process's own.

use std::path::Path;
use std::sync::OnceLock;

/// The identity of a process: host name, kernel boot and PID namespace, and its pid there.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Identity {
    /// The host name, reduced to `[A-Za-z0-9_]` (at most 32 characters; `unknown` if none).
    pub host: String,
    /// The first 12 hex digits of the kernel's boot id (`/proc/sys/kernel/random/boot_id`),
    /// new at every boot of every machine; `0` where it cannot be read.
    pub boot: String,
    /// The inode of the PID namespace (`/proc/self/ns/pid`); `0` where it cannot be read.
    pub pid_ns: String,
    /// The process id in that namespace.
    pub pid: u32,
}

impl Identity {
    /// Whether `self` is known to run on this process's kernel, in its PID namespace and on
    /// a host of the same name: only then does its pid name a process that can be looked up
    /// here. An unknown boot id or namespace never matches.
    pub fn is_local(&self) -> bool {
        let me = this_process();
        self.boot != "0"
            && self.pid_ns != "0"
            && self.boot == me.boot
            && self.pid_ns == me.pid_ns
            && self.host == me.host
    }

    /// Whether the process is known to be gone: it is local ([`Identity::is_local`]) and no
    /// process has its pid. A process that cannot be looked up counts as alive.
    pub fn is_gone(&self) -> bool {
        self.is_local() && self.pid != std::process::id() && process_alive(self.pid) == Some(false)
    }
}

/// This process's identity (read once).
pub fn this_process() -> &'static Identity {
    static ME: OnceLock<Identity> = OnceLock::new();
    ME.get_or_init(|| Identity {
        host: host_name(),
        boot: boot_id(),
        pid_ns: pid_namespace(),
        pid: std::process::id(),
    })
}

/// A host name as it appears in file names: `[A-Za-z0-9_]`, at most 32 characters.
pub fn sanitize_host(name: &str) -> String {
    let s: String = name
        .trim()
        .chars()
        .take(32)
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
        .collect();
    if s.is_empty() { "unknown".into() } else { s }
}

fn host_name() -> String {
    let raw = std::fs::read_to_string("/proc/sys/kernel/hostname")
        .ok()
        .or_else(|| std::env::var("HOSTNAME").ok())
        .or_else(|| std::env::var("COMPUTERNAME").ok())
        .unwrap_or_default();
    sanitize_host(&raw)
}

fn boot_id() -> String {
    let id: String = std::fs::read_to_string("/proc/sys/kernel/random/boot_id")
        .unwrap_or_default()
        .chars()
        .filter(char::is_ascii_hexdigit)
        .take(12)
        .collect();
    if id.len() == 12 { id } else { "0".into() }
}

fn pid_namespace() -> String {
    // "pid:[4026531836]"
    let link = std::fs::read_link("/proc/self/ns/pid").unwrap_or_default();
    let digits: String = link
        .to_string_lossy()
        .chars()
        .filter(char::is_ascii_digit)
        .collect();
    if digits.is_empty() {
        "0".into()
    } else {
        digits
    }
}

/// Whether process `pid` of this process's PID namespace is alive: `Some` on Linux when
/// `/proc` shows this namespace (its `self` is this process's pid; after `unshare --pid`
/// without a new `/proc` it shows the parent's), `None` where it cannot be told.
pub fn process_alive(pid: u32) -> Option<bool> {
    if !cfg!(target_os = "linux") {
        return None;
    }
    let own = std::fs::read_link("/proc/self").ok()?;
    if own.to_str()? != std::process::id().to_string() {
        return None;
    }
    Some(Path::new("/proc").join(pid.to_string()).exists())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn host_names_are_reduced_to_safe_characters() {
        assert_eq!(sanitize_host("node-12.cluster"), "node_12_cluster");
        assert_eq!(sanitize_host(" \n"), "unknown");
        assert_eq!(sanitize_host(&"x".repeat(80)).len(), 32);
    }

    /// On Linux this process is local and alive; another host's process with the same
    /// numbers is not local, so never judged gone.
    #[cfg(target_os = "linux")]
    #[test]
    fn only_a_local_process_can_be_judged_gone() {
        let me = this_process().clone();
        assert!(me.is_local(), "{me:?}");
        assert_eq!(process_alive(me.pid), Some(true));
        let dead = Identity {
            pid: u32::MAX,
            ..me.clone()
        };
        assert!(dead.is_gone());
        for other in [
            Identity {
                host: "elsewhere".into(),
                ..dead.clone()
            },
            Identity {
                boot: "0123456789ab".into(),
                ..dead.clone()
            },
            Identity {
                pid_ns: "1".into(),
                ..dead.clone()
            },
        ] {
            assert!(!other.is_local() && !other.is_gone(), "{other:?}");
        }
    }
}
