//! Plants that advance themselves over a sample period (`Plant::advance`):
//! the loop applies their own update instead of RK4, bit for bit, and stops
//! their lanes by the same rules.

use famcc_core::Controller;
use famcc_paper::designs::{example1, Variant};
use famcc_sim::control::Cores;
use famcc_sim::{Detail, Failure, Lockstep, Options, Plant, Reason, Record};

const DT: f64 = 1e-3;

/// A double integrator `y'' = u` advanced exactly under the held input (the
/// zero-order-hold map), one lane; `rhs` fails, so a loop that integrated it
/// would stop with a plant error. `poison` makes the update non-finite from
/// that sample on, `fail_at` makes it an error there.
struct Exact {
    calls: usize,
    poison: Option<usize>,
    fail_at: Option<usize>,
}

impl Plant for Exact {
    type Error = &'static str;

    fn rhs(&mut self, _: f64, _: &[f64], _: &[f64], _: &mut [f64]) -> Result<(), Self::Error> {
        Err("rhs called on a plant that advances itself")
    }

    fn advance(&mut self, _: f64, dt: f64, x: &mut [f64], u: &[f64]) -> Result<bool, Self::Error> {
        if self.fail_at == Some(self.calls) {
            return Err("the simulator failed");
        }
        let (p, v, a) = (x[0], x[1], u[0]);
        x[0] = p + v * dt + 0.5 * a * dt * dt;
        x[1] = if self.poison.is_some_and(|k| self.calls >= k) {
            f64::NAN
        } else {
            v + a * dt
        };
        self.calls += 1;
        Ok(true)
    }
}

fn exact(poison: Option<usize>, fail_at: Option<usize>) -> Exact {
    Exact {
        calls: 0,
        poison,
        fail_at,
    }
}

fn run(plant: &mut Exact, samples: usize) -> (Record, Lockstep, Result<(), String>) {
    let mut cores = [Controller::new(example1::<f64>(Variant::Code, DT).unwrap())];
    let x0 = vec![-1.0, 1.5];
    let mut sim = Lockstep::new(Options::single(DT, samples, 10, 2, Some((-2.5, 3.0))), x0).unwrap();
    let yd = vec![0.0; samples];
    let mut rec = Record::new(Detail::Full, true);
    let out = sim
        .run(plant, &mut Cores::raising(&mut cores), &yd, None, None, &mut rec)
        .map_err(|f| match f {
            Failure::Plant(k, e) => format!("plant at {k}: {e}"),
            Failure::Controller(k, _) => format!("controller at {k}"),
            Failure::Shape(s) => s.to_string(),
        });
    (rec, sim, out)
}

#[test]
fn a_plant_that_advances_itself_is_stepped_by_its_own_update_bit_for_bit() {
    let samples = 1500;
    // By hand: e_k = p_k, v_k = step(e_k, applied u_{k-1}), u_k = clip(v_k), the exact map.
    let mut ctrl = Controller::new(example1::<f64>(Variant::Code, DT).unwrap());
    let (mut x, mut prev) = ([-1.0f64, 1.5], None);
    let (mut want_v, mut want_x) = (Vec::new(), Vec::new());
    for k in 0..samples {
        want_x.extend_from_slice(&x);
        let v = ctrl.step_applied(x[0], prev).unwrap();
        let u = v.clamp(-2.5, 3.0);
        want_v.push(v);
        if k + 1 < samples {
            x = [x[0] + x[1] * DT + 0.5 * u * DT * DT, x[1] + u * DT];
        }
        prev = Some(u);
    }
    let mut plant = exact(None, None);
    let (rec, sim, out) = run(&mut plant, samples);
    assert_eq!(out, Ok(()));
    assert_eq!(
        plant.calls,
        samples - 1,
        "one advance per sample period, none after the last"
    );
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    assert_eq!(bits(&rec.v), bits(&want_v));
    assert_eq!(bits(&rec.x), bits(&want_x));
    assert!(sim.stops().iter().all(Option::is_none) && sim.done());
}

#[test]
fn a_non_finite_update_stops_the_lane_and_a_failed_one_is_the_plants_error() {
    let mut plant = exact(Some(7), None);
    let (rec, sim, out) = run(&mut plant, 100);
    assert_eq!(out, Ok(()));
    let stop = sim.stops()[0].expect("the lane stopped");
    assert_eq!((stop.samples, stop.reason), (8, Reason::NonFiniteState));
    assert_eq!(rec.rows, 8);

    let mut plant = exact(None, Some(3));
    let (_, sim, out) = run(&mut plant, 100);
    assert_eq!(out, Err("plant at 3: the simulator failed".to_string()));
    let stop = sim.stops()[0].expect("the lane stopped");
    assert_eq!(stop.reason, Reason::PlantError);
}
