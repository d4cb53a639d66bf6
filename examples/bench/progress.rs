//! How far a run is. Each measurement prints one line on standard error, after what it
//! measured: how many measurements are done and left, and an estimate of the time left
//! from the time the done ones took. One line per measurement reads the same on a terminal
//! and in a log.
//!
//! The count is the process's own (the benchmark is one run per process): [`start`] sets
//! the number planned, [`measured!`](crate::measured) counts one.

use std::{
    sync::Mutex,
    time::{Duration, Instant},
};

/// The run under way: measurements planned and done, and when it started.
struct Run {
    planned: usize,
    done: usize,
    started: Instant,
}

static RUN: Mutex<Option<Run>> = Mutex::new(None);

/// Starts a run of `planned` measurements.
pub fn start(planned: usize) {
    *RUN.lock().expect("no measurement panicked") = Some(Run {
        planned,
        done: 0,
        started: Instant::now(),
    });
}

/// Counts one measurement and prints `line` (what it measured) with how far the run is.
pub fn measured(line: std::fmt::Arguments) {
    let mut run = RUN.lock().expect("no measurement panicked");
    let Some(run) = run.as_mut() else {
        // A run that planned nothing (`--one-row`): the line alone.
        eprintln!("{line}");
        return;
    };
    run.done += 1;
    eprintln!("{line}  [{}]", run.how_far());
}

impl Run {
    /// "done of planned, left left, about T left".
    fn how_far(&self) -> String {
        let left = self.planned.saturating_sub(self.done);
        let per_measurement = self.started.elapsed() / self.done.max(1) as u32;
        format!(
            "{} of {} measurements done, {left} left, about {} left",
            self.done,
            self.planned,
            minutes_or_seconds(per_measurement * left as u32)
        )
    }
}

/// `duration` in whole minutes past two minutes, else in seconds.
fn minutes_or_seconds(duration: Duration) -> String {
    let seconds = duration.as_secs();
    if seconds >= 120 {
        format!("{} min", seconds.div_ceil(60))
    } else {
        format!("{seconds} s")
    }
}

/// Prints one measurement's line (as `eprintln!` takes its arguments) and counts it.
#[macro_export]
macro_rules! measured {
    ($($line:tt)*) => {
        $crate::progress::measured(format_args!($($line)*))
    };
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_time_left_is_the_mean_time_so_far_times_the_measurements_left() {
        let run = Run {
            planned: 10,
            done: 4,
            started: Instant::now() - Duration::from_secs(40),
        };
        let line = run.how_far();
        assert!(
            line.starts_with("4 of 10 measurements done, 6 left, about 60 s left"),
            "{line}"
        );
        assert_eq!(minutes_or_seconds(Duration::from_secs(600)), "10 min");
    }
}
