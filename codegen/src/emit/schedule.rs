//! The order of a straight-line body's statements: a list schedule that
//! keeps few values live, so that the compiled function spills and copies
//! fewer registers (its machine code is smaller and faster; see
//! BENCHMARKS.md, "Statements ordered for fewer live values").
//!
//! Each step takes, among the statements whose operands are all computed,
//! the one that ends the most values (operands read for the last time)
//! less the one it starts (its own value, if anything reads it later);
//! ties go to the statement reading the most recently computed value (so a
//! chain of statements is finished before another is begun), then to the
//! earliest in the given order.

use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// The order in which to write `n` statements, given what each reads:
/// `reads[s]` lists the statements (indices below `reads.len()`) and the
/// values given at the start (indices from `reads.len()` on) that statement
/// `s` reads, each once. Every statement comes after those it reads.
pub fn schedule(reads: &[Vec<usize>]) -> Vec<usize> {
    let n = reads.len();
    let values = reads
        .iter()
        .flatten()
        .map(|&v| v + 1)
        .max()
        .unwrap_or(0)
        .max(n);
    let mut readers: Vec<Vec<usize>> = vec![Vec::new(); values];
    for (s, read) in reads.iter().enumerate() {
        for &v in read {
            readers[v].push(s);
        }
    }
    let mut remaining: Vec<usize> = readers.iter().map(Vec::len).collect();
    let mut waiting: Vec<usize> = reads
        .iter()
        .map(|read| read.iter().filter(|&&v| v < n).count())
        .collect();
    let mut ends: Vec<usize> = reads
        .iter()
        .map(|read| read.iter().filter(|&&v| remaining[v] == 1).count())
        .collect();
    let mut done = vec![false; n];
    let by_height = std::env::var("DALEMBERT_SCHED").is_ok_and(|v| v == "height");
    let mut height = vec![0isize; n];
    for s in (0..n).rev() {
        for &r in &readers[s] {
            height[s] = height[s].max(height[r] + 1);
        }
    }
    let score = |s: usize, ends: &[usize], remaining: &[usize]| {
        if by_height {
            return height[s];
        }
        ends[s] as isize - isize::from(remaining[s] > 0)
    };
    // (score, position of the latest operand + 1, earliest statement)
    let mut ready = BinaryHeap::new();
    let mut latest = vec![0usize; n];
    for s in (0..n).filter(|&s| waiting[s] == 0) {
        ready.push((score(s, &ends, &remaining), 0, Reverse(s)));
    }
    let mut order = Vec::with_capacity(n);
    while let Some((priority, _, Reverse(s))) = ready.pop() {
        if done[s] || priority != score(s, &ends, &remaining) {
            continue;
        }
        done[s] = true;
        order.push(s);
        for &v in &reads[s] {
            remaining[v] -= 1;
            if remaining[v] == 1 {
                let last = readers[v].iter().copied().find(|&r| !done[r] && r != s);
                if let Some(r) = last {
                    ends[r] += 1;
                    if waiting[r] == 0 {
                        ready.push((score(r, &ends, &remaining), latest[r], Reverse(r)));
                    }
                }
            }
        }
        for &r in &readers[s] {
            waiting[r] -= 1;
            latest[r] = order.len();
            if waiting[r] == 0 {
                ready.push((score(r, &ends, &remaining), latest[r], Reverse(r)));
            }
        }
    }
    order
}
