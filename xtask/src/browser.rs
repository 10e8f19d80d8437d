//! `cargo xtask page-check` (a step of `cargo xtask test`): builds the report page from a small
//! fixture (`xtask/fixtures/report.json`, with pictures drawn here) into
//! `target/gi-report-fixture/`, opens it in headless Chromium, and checks that it rendered:
//! the DOM holds every chart as inline SVG and the headline answers, and the screenshot is
//! neither blank nor colourless.

use crate::report;
use anyhow::{Context, bail, ensure};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// Set to `1` to skip the browser (only where Chromium cannot be installed; CI installs it).
pub const ENV_SKIP: &str = "SEREIN_SKIP_BROWSER";

fn chromium() -> Option<PathBuf> {
    let path = std::env::var_os("PATH")?;
    for name in ["chromium", "chromium-browser", "google-chrome", "google-chrome-stable"] {
        for dir in std::env::split_paths(&path) {
            let p = dir.join(name);
            if p.is_file() {
                return Some(p);
            }
        }
    }
    None
}

/// Draws the fixture's pictures: a smooth truth and two approximations of it (blocky and
/// noisy), as an image-producing sweep would.
fn fixture_pictures(dir: &Path) -> anyhow::Result<()> {
    use gi_report::pictures::{write_error, write_thumbnail};
    let (w, h) = (192u32, 108u32);
    let truth: Vec<[f32; 3]> = (0..w * h)
        .map(|i| {
            let (x, y) = ((i % w) as f32 / w as f32, (i / w) as f32 / h as f32);
            let lit = if x > 0.55 { 1.0 } else { 0.25 };
            [0.9 * lit * (1.0 - y * 0.5), 0.5 * lit, 0.35 * lit * (0.5 + y)]
        })
        .collect();
    let blocky: Vec<[f32; 3]> = (0..w * h)
        .map(|i| {
            let (x, y) = ((i % w) / 24 * 24 + 12, (i / w) / 24 * 24 + 12);
            truth[(y.min(h - 1) * w + x.min(w - 1)) as usize]
        })
        .collect();
    let noisy: Vec<[f32; 3]> = truth
        .iter()
        .enumerate()
        .map(|(i, c)| {
            let n = ((i as u32).wrapping_mul(2_654_435_761) >> 24) as f32 / 255.0;
            c.map(|v| v * (0.8 + 0.4 * n))
        })
        .collect();
    let out = dir.join(gi_report::PICTURES).join("rsm_gi");
    write_thumbnail(&out.join("truth.png"), &truth, w, h, 1.0)?;
    for (name, img) in [("gather_64", &blocky), ("gather_1024", &noisy)] {
        write_thumbnail(&out.join(format!("{name}.png")), img, w, h, 1.0)?;
        write_error(&out.join(format!("{name}_error.png")), img, &truth, w, h)?;
    }
    Ok(())
}

/// Runs `cmd` with a time limit; returns its stdout.
fn run_limited(cmd: &mut Command, limit: Duration) -> anyhow::Result<String> {
    let out_path =
        std::env::temp_dir().join(format!("serein-page-check-{}.out", std::process::id()));
    let out_file = std::fs::File::create(&out_path)?;
    let mut child = cmd
        .stdout(out_file)
        .stderr(Stdio::null())
        .spawn()
        .with_context(|| format!("starting {cmd:?}"))?;
    let started = Instant::now();
    loop {
        if let Some(status) = child.try_wait()? {
            let out = std::fs::read_to_string(&out_path).unwrap_or_default();
            std::fs::remove_file(&out_path).ok();
            ensure!(status.success(), "{cmd:?} failed: {status}");
            return Ok(out);
        }
        if started.elapsed() > limit {
            child.kill().ok();
            child.wait().ok();
            bail!("{cmd:?} ran past {} s", limit.as_secs());
        }
        std::thread::sleep(Duration::from_millis(100));
    }
}

fn browser(exe: &Path, profile: &Path) -> Command {
    let mut c = Command::new(exe);
    c.args([
        "--headless",
        "--no-sandbox",
        "--disable-gpu",
        "--disable-quic",
        "--no-first-run",
        "--disable-background-networking",
        "--disable-component-update",
        "--disable-sync",
        "--hide-scrollbars",
    ])
    .arg(format!("--user-data-dir={}", profile.display()));
    c
}

/// What the screenshot holds: the share of non-white pixels and of saturated (coloured) ones.
fn screenshot_content(png: &Path) -> anyhow::Result<(u32, u32, f64, f64)> {
    let img = image::open(png).with_context(|| format!("reading {}", png.display()))?.to_rgb8();
    let (w, h) = img.dimensions();
    let (mut ink, mut colour) = (0usize, 0usize);
    for p in img.pixels() {
        let [r, g, b] = p.0;
        if r.min(g).min(b) < 235 {
            ink += 1;
        }
        if r.max(g).max(b) as i32 - r.min(g).min(b) as i32 > 60 {
            colour += 1;
        }
    }
    let n = (w * h) as f64;
    Ok((w, h, ink as f64 / n, colour as f64 / n))
}

/// Builds the fixture's page and checks it in the browser; returns the screenshot's path.
pub fn check(root: &Path) -> anyhow::Result<Option<PathBuf>> {
    let dir = root.join("target/gi-report-fixture");
    if dir.exists() {
        std::fs::remove_dir_all(&dir)?;
    }
    std::fs::create_dir_all(&dir)?;
    std::fs::copy(root.join("xtask/fixtures/report.json"), dir.join("report.json"))?;
    fixture_pictures(&dir)?;
    report::redraw(&dir)?;
    let page = dir.join("index.html");
    let html = std::fs::read_to_string(&page)?;
    let charts = std::fs::read_dir(&dir)?
        .filter(|e| e.as_ref().is_ok_and(|e| e.path().extension().is_some_and(|x| x == "svg")))
        .count();
    ensure!(charts >= 3, "the fixture should give at least 3 charts, got {charts}");

    let Some(exe) = chromium() else {
        if std::env::var(ENV_SKIP).is_ok_and(|v| v == "1") {
            eprintln!(
                "page check: no Chromium, skipped ({ENV_SKIP}=1); the page is {}",
                page.display()
            );
            return Ok(None);
        }
        bail!(
            "page check: no Chromium in PATH (apt-get install -y chromium, as .ci/run does; \
             {ENV_SKIP}=1 skips this step)"
        );
    };
    let url = format!("file://{}", page.canonicalize()?.display());
    let limit = Duration::from_secs(120);

    let profile = dir.join("chromium-profile-dom");
    let dom = run_limited(browser(&exe, &profile).arg("--dump-dom").arg(&url), limit)?;
    let svgs = dom.matches("<svg").count();
    ensure!(
        svgs == charts && svgs == html.matches("<svg").count(),
        "the browser's DOM holds {svgs} inline charts, {charts} were drawn"
    );
    for needle in ["Headline answers", "Pareto front", "id=\"machine\"", "no clear winner", "<img"]
    {
        ensure!(dom.contains(needle), "the rendered page lacks {needle:?}");
    }

    let shot = dir.join("page.png");
    let profile = dir.join("chromium-profile-shot");
    run_limited(
        browser(&exe, &profile)
            .arg("--window-size=1280,2000")
            .arg(format!("--screenshot={}", shot.display()))
            .arg(&url),
        limit,
    )?;
    let (w, h, ink, colour) = screenshot_content(&shot)?;
    eprintln!(
        "page check: {svgs} charts in the DOM; screenshot {w}x{h}: {:.1}% ink, {:.2}% colour",
        100.0 * ink,
        100.0 * colour
    );
    ensure!((w, h) == (1280, 2000), "screenshot is {w}x{h}");
    ensure!(ink > 0.03, "the page looks blank: {:.2}% of its pixels are not white", 100.0 * ink);
    ensure!(colour > 0.001, "the page has no colour (no chart drawn?): {:.3}%", 100.0 * colour);
    for p in ["chromium-profile-dom", "chromium-profile-shot"] {
        std::fs::remove_dir_all(dir.join(p)).ok();
    }
    Ok(Some(shot))
}
