//! Invalid graphs are rejected with errors that name the passes and resources at fault.

mod common;

use frame_scheduler::{Budget, FrameGraph, GraphError, Lane, Res};
use proptest::prelude::*;

type G = FrameGraph<()>;

/// Adds `extra` acyclic GPU passes reading random earlier ones (noise around the fault).
fn noise(g: &mut G, tag: &str, extra: &[u16], feed: Option<Res<u32>>) {
    let mut outs: Vec<Res<u32>> = feed.into_iter().collect();
    for (i, &mask) in extra.iter().enumerate() {
        let r = g.resource::<u32>(format!("{tag} noise{i}"));
        let mut b = g.gpu_pass(format!("{tag} noise pass {i}")).writes(r);
        for (j, &o) in outs.iter().enumerate() {
            if mask & (1 << j) != 0 {
                b = b.reads(o);
            }
        }
        b.run(|_| Ok(()));
        outs.push(r);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(common::cases(64)))]

    #[test]
    fn cycles_are_rejected_naming_a_real_cycle(len in 1usize..8, extra in prop::collection::vec(any::<u16>(), 0..8), rot in 0usize..8) {
        let mut g = G::new();
        let res: Vec<Res<u32>> = (0..len).map(|i| g.resource(format!("c{i}"))).collect();
        noise(&mut g, "a", &extra, None);
        // c_i is written by "cycle i" and read by "cycle i+1" (mod len); declared rotated.
        for k in 0..len {
            let i = (k + rot) % len;
            g.gpu_pass(format!("cycle {i}")).reads(res[(i + len - 1) % len]).writes(res[i]).run(|_| Ok(()));
        }
        noise(&mut g, "b", &extra, Some(res[0]));
        let err = g.build().err().expect("a cycle is an error");
        let GraphError::Cycle { passes } = &err else { panic!("expected a cycle, got {err}") };
        prop_assert_eq!(passes.len(), len);
        // The named passes are the cycle, each feeding the next.
        let idx: Vec<usize> = passes.iter().map(|p| p.strip_prefix("cycle ").expect("only cycle passes").parse().unwrap()).collect();
        for w in 0..len {
            prop_assert_eq!(idx[(w + 1) % len], (idx[w] + 1) % len);
        }
        let msg = err.to_string();
        prop_assert!(passes.iter().all(|p| msg.contains(p.as_str())), "{}", msg);
    }

    #[test]
    fn double_writers_are_rejected_naming_both(extra in prop::collection::vec(any::<u16>(), 0..8), lanes in (0u8..3, 0u8..3)) {
        let lane = |v: u8| [Lane::Cpu, Lane::Gpu, Lane::Sync][v as usize];
        let mut g = G::new();
        noise(&mut g, "a", &extra, None);
        let shared = g.resource::<u32>("sky map");
        g.pass("first writer", lane(lanes.0)).writes(shared).run(|_| Ok(()));
        noise(&mut g, "b", &extra, None);
        g.pass("second writer", lane(lanes.1)).writes(shared).run(|_| Ok(()));
        let err = g.build().err().expect("two writers is an error");
        prop_assert_eq!(&err, &GraphError::DoubleWriter {
            resource: "sky map".into(),
            writers: vec!["first writer".into(), "second writer".into()],
        });
        let msg = err.to_string();
        prop_assert!(msg.contains("'first writer'") && msg.contains("'second writer'") && msg.contains("sky map"));
    }

    #[test]
    fn missing_producers_are_rejected_naming_readers(extra in prop::collection::vec(any::<u16>(), 0..8)) {
        let mut g = G::new();
        noise(&mut g, "a", &extra, None);
        let orphan = g.resource::<u32>("shadow map");
        let out = g.resource::<u32>("lit");
        g.gpu_pass("lighting").reads(orphan).writes(out).run(|_| Ok(()));
        let err = g.build().err().expect("a missing producer is an error");
        prop_assert_eq!(&err, &GraphError::MissingProducer { resource: "shadow map".into(), readers: vec!["lighting".into()] });
        prop_assert!(err.to_string().contains("'lighting'"));
    }
}

#[test]
fn a_pass_reading_its_own_output_is_a_cycle_of_one() {
    let mut g = G::new();
    let r = g.resource::<u32>("history");
    g.gpu_pass("taa").reads(r).writes(r).run(|_| Ok(()));
    assert_eq!(g.build().err(), Some(GraphError::Cycle { passes: vec!["taa".into()] }));
}

#[test]
fn cpu_and_gpu_exchange_data_only_through_sync_points() {
    let mut g = G::new();
    let traced = g.resource::<u32>("traced G-buffer");
    g.cpu_job("ray tracing").writes(traced).run(|_| Ok(()));
    g.gpu_pass("reflections").reads(traced).run(|_| Ok(()));
    let err = g.build().err().unwrap();
    assert!(
        matches!(&err, GraphError::NeedsSync { reader, writer, .. } if reader == "reflections" && writer == "ray tracing")
    );
    assert!(err.to_string().contains("sync"), "{err}");

    let mut g = G::new();
    let rays = g.resource::<u32>("rays");
    g.gpu_pass("ray casting").writes(rays).run(|_| Ok(()));
    g.cpu_job("ray tracing").reads(rays).run(|_| Ok(()));
    assert!(matches!(g.build().err(), Some(GraphError::NeedsSync { .. })));
}

#[test]
fn inputs_foreign_handles_names_and_budgets_are_checked() {
    let mut g = G::new();
    let input = g.input::<u32>("camera");
    g.gpu_pass("writer").writes(input).run(|_| Ok(()));
    assert!(matches!(g.build().err(), Some(GraphError::WritesInput { .. })));

    let mut other = G::new();
    let foreign = other.resource::<u32>("elsewhere");
    let mut g = G::new();
    g.gpu_pass("confused").reads(foreign).run(|_| Ok(()));
    assert_eq!(g.build().err(), Some(GraphError::ForeignHandle { pass: "confused".into() }));

    let mut g = G::new();
    g.gpu_pass("twin").side_effect().run(|_| Ok(()));
    g.gpu_pass("twin").side_effect().run(|_| Ok(()));
    assert_eq!(g.build().err(), Some(GraphError::DuplicatePass { name: "twin".into() }));

    for budget in
        [Budget::Units(0), Budget::Millis(0.0), Budget::Millis(f64::NAN), Budget::Millis(-1.0)]
    {
        let mut g = G::new();
        g.gpu_pass("sky").side_effect().amortised(16, budget).run(|_| Ok(()));
        assert!(matches!(g.build().err(), Some(GraphError::BadAmortisation { .. })), "{budget:?}");
    }
    let mut g = G::new();
    g.gpu_pass("sky").side_effect().amortised(0, Budget::Units(1)).run(|_| Ok(()));
    assert!(matches!(g.build().err(), Some(GraphError::BadAmortisation { .. })));
}
