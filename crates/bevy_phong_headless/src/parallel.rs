//! Work shared among the machine's cores ([`parallel_map`]), with a progress line for long
//! runs ([`Progress`]).

use std::{
    io::{IsTerminal, Write},
    num::NonZero,
    sync::{
        Mutex,
        atomic::{AtomicUsize, Ordering},
    },
    time::{Duration, Instant},
};

/// How many items a thread takes at a time: small enough that the costly ones (pixels lit
/// by area lights) spread over the threads, large enough that taking them costs nothing.
const BATCH: usize = 256;

/// `each` of `0..count`, in order, computed on every core: each thread takes the next batch
/// of [`BATCH`] items until none are left. The batches are taken spread over the range (a
/// stride coprime to their number), so that the share done is a fair estimate of the work
/// done where the costly items are bunched (an image's lit rows). With `progress`, it
/// reports how far the work is.
pub fn parallel_map<T: Send>(
    count: usize,
    each: impl Fn(usize) -> T + Sync,
    mut progress: Option<&mut Progress>,
) -> Vec<T> {
    let batch_count = count.div_ceil(BATCH);
    let threads = std::thread::available_parallelism()
        .map_or(1, NonZero::get)
        .min(batch_count)
        .max(1);
    let stride = coprime_stride(batch_count);
    let next = AtomicUsize::new(0);
    let done = AtomicUsize::new(0);
    let batches: Mutex<Vec<(usize, Vec<T>)>> = Mutex::new(Vec::new());
    std::thread::scope(|scope| {
        let workers: Vec<_> = (0..threads)
            .map(|_| {
                scope.spawn(|| {
                    loop {
                        let taken = next.fetch_add(1, Ordering::Relaxed);
                        if taken >= batch_count {
                            break;
                        }
                        let start = taken * stride % batch_count * BATCH;
                        let end = (start + BATCH).min(count);
                        let batch: Vec<T> = (start..end).map(&each).collect();
                        done.fetch_add(end - start, Ordering::Relaxed);
                        batches
                            .lock()
                            .expect("a worker panicked")
                            .push((start, batch));
                    }
                })
            })
            .collect();
        if let Some(progress) = progress.as_deref_mut() {
            while workers.iter().any(|worker| !worker.is_finished()) {
                progress.report(done.load(Ordering::Relaxed));
                std::thread::sleep(Duration::from_millis(100));
            }
        }
        for worker in workers {
            if let Err(panic) = worker.join() {
                std::panic::resume_unwind(panic);
            }
        }
    });
    if let Some(progress) = progress {
        progress.finish();
    }
    let mut batches = batches.into_inner().expect("every worker finished");
    batches.sort_unstable_by_key(|&(start, _)| start);
    batches.into_iter().flat_map(|(_, batch)| batch).collect()
}

/// A step through `0..count` that visits each once (`i · stride mod count`): about 0.618 of
/// `count`, the golden ratio's share, made coprime to it.
fn coprime_stride(count: usize) -> usize {
    let gcd = |mut a: usize, mut b: usize| {
        while b != 0 {
            (a, b) = (b, a % b);
        }
        a
    };
    let mut stride = (count as f64 * 0.618) as usize;
    while stride > 1 && gcd(stride, count) != 1 {
        stride += 1;
    }
    stride.max(1)
}

/// A progress line on standard error: items done, items left and an estimate of the time
/// left, drawn over itself where standard error is a terminal, else a plain line every tenth
/// of the work (for logs).
pub struct Progress {
    what: String,
    total: usize,
    started: Instant,
    terminal: bool,
    /// The last tenth of the work reported (logs).
    last_tenth: usize,
    /// When the line was last drawn (a terminal).
    last_drawn: Option<Instant>,
}

impl Progress {
    /// A progress line for `total` items of `what` (a plural noun: "pixels", "rows").
    pub fn new(what: impl Into<String>, total: usize) -> Self {
        Self {
            what: what.into(),
            total,
            started: Instant::now(),
            terminal: std::io::stderr().is_terminal(),
            last_tenth: 0,
            last_drawn: None,
        }
    }

    /// Reports that `done` items are done (at most once a second on a terminal).
    pub fn report(&mut self, done: usize) {
        let tenth = done * 10 / self.total.max(1);
        let due = if self.terminal {
            self.last_drawn
                .is_none_or(|drawn| drawn.elapsed() >= Duration::from_secs(1))
        } else {
            tenth > self.last_tenth
        };
        if !due {
            return;
        }
        self.last_tenth = tenth;
        self.last_drawn = Some(Instant::now());
        let line = self.line(done);
        let mut stderr = std::io::stderr().lock();
        let _ = if self.terminal {
            write!(stderr, "\r{line}\x1b[K")
        } else {
            writeln!(stderr, "{line}")
        };
        let _ = stderr.flush();
    }

    /// Ends the line (on a terminal), with the time the work took.
    pub fn finish(&mut self) {
        let line = format!(
            "{}: {} done in {:.1} s",
            self.what,
            self.total,
            self.started.elapsed().as_secs_f64()
        );
        let mut stderr = std::io::stderr().lock();
        let _ = if self.terminal {
            writeln!(stderr, "\r{line}\x1b[K")
        } else {
            writeln!(stderr, "{line}")
        };
    }

    /// "what: done of total (p %), left, about t s left".
    fn line(&self, done: usize) -> String {
        let elapsed = self.started.elapsed().as_secs_f64();
        let left = self.total.saturating_sub(done);
        let estimate = if done == 0 {
            String::from("time left not known yet")
        } else {
            format!("about {:.0} s left", elapsed / done as f64 * left as f64)
        };
        format!(
            "{}: {done} of {} done ({:.0} %), {left} left, {estimate}",
            self.what,
            self.total,
            100.0 * done as f64 / self.total.max(1) as f64
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_item_is_computed_once_and_in_order() {
        let squares = parallel_map(10_000, |index| index * index, None);
        assert_eq!(squares.len(), 10_000);
        assert!(
            squares
                .iter()
                .enumerate()
                .all(|(index, &square)| square == index * index)
        );
        assert!(parallel_map(0, |index| index, None).is_empty());
        for count in [1, 2, 10, 257, 1000] {
            let stride = coprime_stride(count);
            let mut visited: Vec<usize> = (0..count).map(|i| i * stride % count).collect();
            visited.sort_unstable();
            assert!(
                visited.into_iter().eq(0..count),
                "stride {stride} of {count}"
            );
        }
    }

    #[test]
    fn the_line_says_what_is_done_and_left() {
        let progress = Progress::new("pixels", 200);
        let line = progress.line(50);
        assert!(
            line.starts_with("pixels: 50 of 200 done (25 %), 150 left, about"),
            "{line}"
        );
    }
}
