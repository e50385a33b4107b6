//! A plotted line's envelope: over each slice of simulated time its lowest
//! and highest point, kept up as the samples come, so that drawing a line
//! costs its slices, not its samples (30 s are 3 600 of them), and a swing
//! quicker than a slice (a tumbler rocking) still shows its whole extent.

use std::collections::VecDeque;

/// One slice of time's lowest and highest point, each `[time, value]`.
#[derive(Clone, Copy, Debug)]
struct Slice {
    /// Which slice: its start over the slices' width.
    number: i64,
    low: [f64; 2],
    high: [f64; 2],
}

/// A line's lowest and highest point in each slice of time, and its last.
#[derive(Clone, Debug)]
pub struct Envelope {
    /// The slices' width (s).
    width: f64,
    slices: VecDeque<Slice>,
    last: Option<[f64; 2]>,
}

impl Envelope {
    /// An empty line whose slices are `width` seconds wide.
    pub fn new(width: f64) -> Envelope {
        Envelope {
            width,
            slices: VecDeque::new(),
            last: None,
        }
    }

    /// Adds the point `value` at `time`, later than every point before. A
    /// value that is not a number is kept only where the slice has no other.
    pub fn push(&mut self, time: f64, value: f64) {
        let number = (time / self.width).floor() as i64;
        let point = [time, value];
        self.last = Some(point);
        match self.slices.back_mut() {
            Some(slice) if slice.number == number => {
                if value < slice.low[1] || slice.low[1].is_nan() {
                    slice.low = point;
                }
                if value > slice.high[1] || slice.high[1].is_nan() {
                    slice.high = point;
                }
            }
            _ => self.slices.push_back(Slice {
                number,
                low: point,
                high: point,
            }),
        }
    }

    /// Forgets the slices that end before `time`.
    pub fn forget_before(&mut self, time: f64) {
        let first = (time / self.width).floor() as i64;
        while self.slices.front().is_some_and(|s| s.number < first) {
            self.slices.pop_front();
        }
    }

    /// The points to draw: each slice's lowest and highest in their order,
    /// then the last point added, so that the line ends where it stands.
    pub fn points(&self) -> Vec<[f64; 2]> {
        let mut points = self.points_before(f64::INFINITY);
        if let Some(last) = self.last
            && points.last().is_some_and(|p| p[0] < last[0])
        {
            points.push(last);
        }
        points
    }

    /// The slices' lowest and highest points before `time`, in their
    /// order: where a plot draws every sample from `time` on.
    pub fn points_before(&self, time: f64) -> Vec<[f64; 2]> {
        let mut points = Vec::with_capacity(2 * self.slices.len() + 1);
        for slice in &self.slices {
            let (first, second) = if slice.low[0] <= slice.high[0] {
                (slice.low, slice.high)
            } else {
                (slice.high, slice.low)
            };
            for point in [first, second] {
                if point[0] < time && points.last().is_none_or(|p: &[f64; 2]| p[0] < point[0]) {
                    points.push(point);
                }
            }
        }
        points
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `n` points of a sine of `period` seconds, sampled at 120 Hz.
    fn sine(n: usize, period: f64) -> impl Iterator<Item = [f64; 2]> {
        (0..n).map(move |k| {
            let t = k as f64 / 120.0;
            [t, (std::f64::consts::TAU * t / period).sin()]
        })
    }

    #[test]
    fn every_slice_keeps_its_extremes_in_time_order_and_the_line_ends_where_it_stands() {
        for (n, period, width) in [(3_600, 0.06, 0.2), (1_000, 0.5, 0.3), (50, 1.0, 0.1)] {
            let mut line = Envelope::new(width);
            for [t, v] in sine(n, period) {
                line.push(t, v);
            }
            let points = line.points();
            let slices = ((n - 1) as f64 / 120.0 / width).floor() as usize + 1;
            assert!(points.len() <= 2 * slices + 1, "{}", points.len());
            assert!(
                points.windows(2).all(|w| w[0][0] < w[1][0]),
                "in time order"
            );
            assert_eq!(points.last(), sine(n, period).last().as_ref());
            // Each slice's highest and lowest sample is drawn.
            let all: Vec<[f64; 2]> = sine(n, period).collect();
            for number in 0..slices as i64 {
                let inside = all
                    .iter()
                    .filter(|p| (p[0] / width).floor() as i64 == number);
                let top = inside.clone().map(|p| p[1]).fold(f64::MIN, f64::max);
                let bottom = inside.map(|p| p[1]).fold(f64::MAX, f64::min);
                assert!(points.iter().any(|p| p[1] == top), "{n} {number}");
                assert!(points.iter().any(|p| p[1] == bottom), "{n} {number}");
            }
        }
    }

    #[test]
    fn what_is_forgotten_is_the_slices_before_and_a_gap_is_no_number() {
        let mut line = Envelope::new(1.0);
        for k in 0..100 {
            let t = f64::from(k) * 0.1;
            line.push(t, if k == 35 { f64::NAN } else { t });
        }
        line.forget_before(3.2);
        let points = line.points();
        assert_eq!(points.first().unwrap()[0], 3.0);
        assert!(points.iter().all(|p| p[1].is_finite()), "{points:?}");
        let before = line.points_before(5.05);
        assert_eq!(before.last().unwrap()[0], 5.0);
        assert!(line.points().len() > before.len());
        let mut gaps = Envelope::new(1.0);
        gaps.push(0.0, f64::NAN);
        assert!(gaps.points()[0][1].is_nan());
    }
}
