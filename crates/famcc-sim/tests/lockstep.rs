//! The loop against a hand-written sample-and-hold loop, lanes against
//! single runs, blocks against one block, and the stop rules.

use famcc_core::Controller;
use famcc_paper::designs::{example1, example3, Variant};
use famcc_paper::plants::{Clock, Plant as _, SecondOrder};
use famcc_paper::rk4::rk4_with;
use famcc_sim::control::Cores;
use famcc_sim::{Detail, Lockstep, Options, PaperLanes, Reason, Record};

const DT: f64 = 1e-3;

fn sine(k: usize) -> f64 {
    (k as f64 * DT).sin()
}

#[test]
fn one_lane_is_the_sample_and_hold_loop_bit_for_bit() {
    let (samples, substeps, limits) = (2000, 10, (-2.5, 3.0));
    // By hand: e_k = x1 - sin t_k, v_k = step(e_k, applied u_{k-1}), u_k = clip(v_k), RK4 substeps.
    let plant = SecondOrder::new(Variant::Code);
    let mut ctrl = Controller::new(example1::<f64>(Variant::Code, DT).unwrap());
    let mut x = plant.x0;
    let (mut want_v, mut want_x) = (Vec::new(), Vec::new());
    let mut prev = None;
    for k in 0..samples {
        want_x.extend_from_slice(&x);
        let v = ctrl.step_applied(x[0] - sine(k), prev).unwrap();
        let u = v.max(limits.0).min(limits.1);
        want_v.push(v);
        if k + 1 < samples {
            let t = k as f64 * DT;
            let h = DT / substeps as f64;
            for j in 0..substeps {
                let tj = t + j as f64 * h;
                x = rk4_with(|i, s| plant.rhs(&Clock::at(i.time(tj, h)), s, u), &x, h);
            }
        }
        prev = Some(u);
    }
    let mut lanes = PaperLanes::second(Variant::Code, vec![1.0], vec![3.0]);
    let mut cores = [Controller::new(example1::<f64>(Variant::Code, DT).unwrap())];
    let mut sim = Lockstep::new(
        Options::single(DT, samples, substeps, 2, Some(limits)),
        lanes.x0(),
    )
    .unwrap();
    let yd: Vec<f64> = (0..samples).map(sine).collect();
    let mut rec = Record::new(Detail::Full, true);
    sim.run(
        &mut lanes,
        &mut Cores::raising(&mut cores),
        &yd,
        None,
        None,
        &mut rec,
    )
    .unwrap();
    assert_eq!(rec.rows, samples);
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(&rec.v), bits(&want_v));
    assert_eq!(bits(&rec.x), bits(&want_x));
    assert_eq!(rec.width, 11 + 2);
    assert!(sim.stops().iter().all(Option::is_none) && sim.done());
}

fn third_order_run(gains: &[f64], blocks: &[usize]) -> (Record, Vec<Option<famcc_sim::Stop>>) {
    let n = gains.len();
    let mut lanes = PaperLanes::third(Variant::Code, gains.to_vec(), vec![10.0; n]);
    let mut cores: Vec<_> = (0..n)
        .map(|_| Controller::new(example3::<f64>(Variant::Code, DT).unwrap()))
        .collect();
    let samples: usize = blocks.iter().sum();
    let mut opts = Options::single(DT, samples, 1, 3, Some((-7.0, 9.0)));
    opts.lanes = n;
    let mut sim = Lockstep::new(opts, lanes.x0()).unwrap();
    let mut rec = Record::new(Detail::Campaign, false);
    let mut k0 = 0;
    for &b in blocks {
        let yd: Vec<f64> = (k0..k0 + b)
            .flat_map(|k| std::iter::repeat_n(sine(k), n))
            .collect();
        sim.run(
            &mut lanes,
            &mut Cores::holding(&mut cores),
            &yd,
            None,
            None,
            &mut rec,
        )
        .unwrap();
        k0 += b;
    }
    (rec, sim.stops().to_vec())
}

#[test]
fn lanes_equal_single_runs_and_blocks_equal_one_block() {
    let gains = [0.8, 1.0, 1.2];
    let (all, _) = third_order_run(&gains, &[1500]);
    let (split, _) = third_order_run(&gains, &[700, 1, 799]);
    assert_eq!(all, split);
    for (l, g) in gains.iter().enumerate() {
        let (one, _) = third_order_run(&[*g], &[1500]);
        let lane: Vec<u64> = all.v.iter().skip(l).step_by(3).map(|x| x.to_bits()).collect();
        assert_eq!(
            lane,
            one.v.iter().map(|x| x.to_bits()).collect::<Vec<_>>(),
            "lane {l}"
        );
        let diag: Vec<f64> = all.diag.chunks(2).skip(l).step_by(3).flatten().copied().collect();
        assert_eq!(diag, one.diag);
    }
}

#[test]
fn a_lane_beyond_diverge_at_stops_there_with_a_partial_row() {
    let mut lanes = PaperLanes::second(Variant::Code, vec![1.0, 1.0], vec![3.0, 3.0]);
    let mut cores = [(); 2].map(|_| Controller::new(example1::<f64>(Variant::Code, DT).unwrap()));
    let mut opts = Options::single(DT, 100, 1, 2, None);
    opts.lanes = 2;
    opts.diverge_at = Some(2.5);
    let mut sim = Lockstep::new(opts, lanes.x0()).unwrap();
    // Lane 1's reference jumps by 3 at sample 40: |e| > 2.5 there.
    let yd: Vec<f64> = (0..100)
        .flat_map(|k| [sine(k), sine(k) + if k >= 40 { 3.0 } else { 0.0 }])
        .collect();
    let mut rec = Record::new(Detail::Full, true);
    sim.run(
        &mut lanes,
        &mut Cores::raising(&mut cores),
        &yd,
        None,
        None,
        &mut rec,
    )
    .unwrap();
    let stop = sim.stops()[1].unwrap();
    assert_eq!((stop.samples, stop.reason), (41, Reason::Diverged));
    assert!(sim.stops()[0].is_none());
    let at = |col: &[f64], k: usize, l: usize| col[k * 2 + l];
    assert!(at(&rec.v, 40, 1).is_nan() && at(&rec.e, 40, 1) < -2.5);
    assert_eq!(at(&rec.u, 40, 1), at(&rec.u, 39, 1)); // the input still held
    assert!(at(&rec.e, 41, 1).is_nan() && at(&rec.v, 41, 0).is_finite());
    assert!(rec.diag[(40 * 2 + 1) * 13].is_nan()); // no diagnostics of the partial row
}

#[test]
fn a_state_beyond_state_bound_stops_the_lane_after_the_kept_sample() {
    let mut lanes = PaperLanes::second(Variant::Code, vec![1.0], vec![3.0]);
    let mut cores = [Controller::new(example1::<f64>(Variant::Code, DT).unwrap())];
    let mut opts = Options::single(DT, 1000, 1, 2, None);
    opts.state_bound = Some(0.9); // x1(0) = -1, x2(0) = 0.5: the first integration leaves it
    assert!(Lockstep::new(opts.clone(), vec![-1.0, f64::NAN]).is_err());
    let mut sim = Lockstep::new(opts, lanes.x0()).unwrap();
    let yd = vec![0.0; 1000];
    let mut rec = Record::new(Detail::None, false);
    sim.run(
        &mut lanes,
        &mut Cores::raising(&mut cores),
        &yd,
        None,
        None,
        &mut rec,
    )
    .unwrap();
    let stop = sim.stops()[0].unwrap();
    assert_eq!((stop.samples, stop.reason, rec.rows), (1, Reason::StateBound, 1));
    assert!(sim.done() && rec.v[0].is_finite());
}

#[test]
fn bad_shapes_and_options_are_refused() {
    let mut lanes = PaperLanes::second(Variant::Code, vec![1.0], vec![3.0]);
    let mut cores = [Controller::new(example1::<f64>(Variant::Code, DT).unwrap())];
    let mut opts = Options::single(DT, 10, 1, 2, Some((1.0, -1.0)));
    assert!(Lockstep::new(opts.clone(), lanes.x0()).is_err());
    opts.limits = vec![None];
    let mut sim = Lockstep::new(opts, lanes.x0()).unwrap();
    let mut rec = Record::new(Detail::None, false);
    let r = sim.run(
        &mut lanes,
        &mut Cores::raising(&mut cores),
        &[0.0; 4],
        Some(&[0.0; 3]),
        None,
        &mut rec,
    );
    assert!(matches!(r, Err(famcc_sim::Failure::Shape(_))));
    assert_eq!(rec.rows, 0);
}
