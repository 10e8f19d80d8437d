//! Generates the reference city, prints its statistics, what it needs from the engine and why,
//! and what changes when the sun moves and a mesh is moved.
//!
//! `cargo run -p serein-scene --release --example city_stats -- [seed]`

use scene::{Generated, SceneChange, SunPosition};
use std::time::Instant;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let seed = std::env::args().nth(1).map(|s| s.parse()).transpose()?.unwrap_or(1u64);
    let t = Instant::now();
    let mut city = Generated::City.build(seed);
    let build_ms = t.elapsed().as_secs_f64() * 1e3;
    city.validate()?;
    println!("city (seed {seed}), generated with texture mips in {build_ms:.1} ms\n");
    println!("{}\n", city.stats());
    if let Some(sun) = &city.sun {
        println!("sun elevation     {:.1}°", sun.elevation_deg()?);
    }
    let v = city.sky_volume;
    println!(
        "sky volume        {} probes over {:.0} x {:.0} x {:.0} m",
        v.resolution,
        v.bounds.size().x,
        v.bounds.size().y,
        v.bounds.size().z
    );
    println!(
        "LPV cascades      {:?} m cells ({} cells a side)\n",
        city.lpv.cell_sizes, city.lpv.resolution
    );

    let t = Instant::now();
    let needs = city.needs();
    println!(
        "what the city needs (SceneNeeds in {:.3} ms):\n{needs}\n",
        t.elapsed().as_secs_f64() * 1e3
    );

    let before = city.state();
    if let Some(s) = &mut city.sun
        && let SunPosition::Time { utc_hours, .. } = &mut s.position
    {
        *utc_hours += 0.25;
    }
    city.meshes[3].transform.translation += glam::Vec3A::new(0.0, 0.5, 0.0);
    let change = SceneChange::between(&before, &city.state());
    println!("after 15 minutes and lifting mesh 3 by 0.5 m: {change}");
    println!(
        "sky volume must be recomputed (threshold 1°): {}",
        change.sky_volume_invalidated(1.0)
    );
    Ok(())
}
