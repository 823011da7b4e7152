//! The process's CPU time around a run, and its time waiting for a core: each
//! thread's `/proc/self/task/<tid>/schedstat` (Linux; its first two fields are the
//! nanoseconds the thread ran and the nanoseconds it was ready to run while every core
//! was busy). On a machine shared with other jobs a run on two threads gets less than
//! two cores: the waiting time says how much less, so that a thread speed-up can be
//! read for what it is.

use std::fs;

/// CPU time and waiting time summed over the process's threads, seconds.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CpuTimes {
    /// Time the threads ran.
    pub run_s: f64,
    /// Time the threads were ready to run but waited for a core.
    pub waited_s: f64,
}

impl CpuTimes {
    /// The process's times so far (`None` where the system keeps no schedstat).
    pub fn now() -> Option<Self> {
        let mut total = Self::default();
        for task in fs::read_dir("/proc/self/task").ok()?.flatten() {
            // A thread that ended since the listing has no file left: it is not counted.
            if let Some(times) = task_times(&task.path()) {
                total.run_s += times.run_s;
                total.waited_s += times.waited_s;
            }
        }
        Some(total)
    }

    /// The times spent since `earlier`.
    pub fn since(self, earlier: Self) -> Self {
        Self {
            run_s: self.run_s - earlier.run_s,
            waited_s: self.waited_s - earlier.waited_s,
        }
    }
}

/// The times of the thread whose `/proc` directory is `task` (`None`: no schedstat,
/// or the thread has ended).
fn task_times(task: &std::path::Path) -> Option<CpuTimes> {
    let text = fs::read_to_string(task.join("schedstat")).ok()?;
    let (run_s, waited_s) = parse_schedstat(&text)?;
    Some(CpuTimes { run_s, waited_s })
}

/// The run and wait times of one `schedstat` line (`run_ns wait_ns timeslices`), seconds.
fn parse_schedstat(text: &str) -> Option<(f64, f64)> {
    let mut fields = text.split_whitespace().map(|f| f.parse::<u64>().ok());
    let run = fields.next()??;
    let waited = fields.next()??;
    Some((run as f64 * 1e-9, waited as f64 * 1e-9))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_schedstat_line_gives_run_and_wait_seconds() {
        assert_eq!(
            parse_schedstat("1500000000 250000000 42\n"),
            Some((1.5, 0.25))
        );
        assert_eq!(parse_schedstat("garbage"), None);
    }

    #[test]
    fn work_on_this_thread_shows_as_cpu_time_on_linux() {
        if !cfg!(target_os = "linux") {
            // Other systems may keep no schedstat: the report shows `–` there.
            return;
        }
        // This thread alone: the process's sum drops when another test's thread ends.
        let this = std::path::Path::new("/proc/thread-self");
        let before = task_times(this).expect("Linux keeps schedstat");
        let mut x = 0u64;
        let started = std::time::Instant::now();
        while started.elapsed().as_millis() < 30 {
            x = std::hint::black_box(x.wrapping_mul(31).wrapping_add(7));
        }
        let spent = task_times(this).unwrap().since(before);
        assert!(spent.run_s > 0.0 && spent.waited_s >= 0.0, "{spent:?}");
        assert!(CpuTimes::now().is_some_and(|t| t.run_s >= spent.run_s));
    }
}
