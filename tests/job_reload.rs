//! `RenderJob::reload` after an edit: the model and the renderer kept when the patch files did
//! not change, so the next frame reuses the tessellation and the surfaces; a new model when
//! they did; a broken edit leaves the job as it was.

use glint::job::{Overrides, Reloaded, RenderJob};
use glint::render::Stage;
use glint::shot::Preset;

use crate::common::ball_shot::{save_as_an_editor_does, BallShot};

/// The one-frame shot of the ball, 40×30, with a highlight of width `epsilon` and its ramp's lit
/// colour `lit`; `include` names an include file if any.
fn shot_text(epsilon: f32, lit: &str, include: Option<&str>) -> String {
    BallShot {
        size: (40, 30),
        epsilon,
        lit,
        include,
        preset: None,
    }
    .text()
}

fn sphere(radius: f32) -> String {
    format!("(patches: [(name: \"sphere\", surface: Sphere(radius: {radius}))])")
}

fn overrides() -> Overrides {
    Overrides {
        preset: Some(Preset::Preview),
        ..Overrides::default()
    }
}

#[test]
fn an_edit_that_keeps_the_patch_files_keeps_the_model_and_the_surfaces() {
    let dir = tempfile::tempdir().unwrap();
    let (shot, model) = (dir.path().join("ball.ron"), dir.path().join("sphere.ron"));
    save_as_an_editor_does(&model, &sphere(1.0));
    save_as_an_editor_does(&shot, &shot_text(0.05, "(0.2, 0.3, 0.7)", None));
    let mut job = RenderJob::load(&shot, &overrides()).unwrap();
    let before = job.render_frame(1.0).unwrap();
    let library = std::sync::Arc::clone(&job.shot().library);

    save_as_an_editor_does(&shot, &shot_text(0.12, "(0.2, 0.3, 0.7)", None));
    assert_eq!(job.reload().unwrap(), Reloaded::ModelKept);
    assert!(std::sync::Arc::ptr_eq(&library, &job.shot().library));
    let after = job.render_frame(1.0).unwrap();
    for stage in [Stage::Tessellate, Stage::Rasterize, Stage::GBuffer] {
        assert!(after.stats.reused(stage), "{stage}");
    }
    assert!(after.stats.ran(Stage::Shade));
    assert_ne!(before.colour, after.colour, "the wider highlight shows");
    let fresh = RenderJob::load(&shot, &overrides())
        .unwrap()
        .render_frame(1.0)
        .unwrap();
    assert_eq!(after.colour, fresh.colour);

    // The patch file changes: a new model, tessellated anew.
    save_as_an_editor_does(&model, &sphere(0.8));
    assert_eq!(job.reload().unwrap(), Reloaded::ModelChanged);
    assert!(!std::sync::Arc::ptr_eq(&library, &job.shot().library));
    let smaller = job.render_frame(1.0).unwrap();
    assert!(smaller.stats.ran(Stage::Tessellate) && smaller.stats.tessellation_rebuilt);
    assert!(smaller.stats[Stage::Rasterize].pixels < before.stats[Stage::Rasterize].pixels);
}

#[test]
fn a_broken_edit_leaves_the_job_and_a_new_include_joins_the_inputs() {
    let dir = tempfile::tempdir().unwrap();
    let (shot, model) = (dir.path().join("ball.ron"), dir.path().join("sphere.ron"));
    save_as_an_editor_does(&model, &sphere(1.0));
    save_as_an_editor_does(&shot, &shot_text(0.05, "(0.2, 0.3, 0.7)", None));
    let mut job = RenderJob::load(&shot, &overrides()).unwrap();
    let good = job.render_frame(1.0).unwrap();
    assert_eq!(job.inputs().len(), 2);

    save_as_an_editor_does(&shot, &shot_text(0.05, "(0.2, 0.3)", None));
    let error = job.reload().unwrap_err();
    assert!(error.is_bad_input());
    assert!(
        error
            .to_string()
            .starts_with(&format!("{}:", shot.display())),
        "{error}"
    );
    assert_eq!(job.render_frame(1.0).unwrap().colour, good.colour);

    let looks = dir.path().join("looks.ron");
    save_as_an_editor_does(&looks, "Looks(materials: {})");
    save_as_an_editor_does(
        &shot,
        &shot_text(0.05, "(0.2, 0.3, 0.7)", Some("looks.ron")),
    );
    job.reload().unwrap();
    assert_eq!(job.inputs().len(), 3);
    assert!(job.inputs().iter().any(|p| p.ends_with("looks.ron")));
}
