//! `glint farm slurm --print`: the job array's script — its chunks, memory, requeue and paths —
//! run here by bash as one Slurm task would run it (the scheduler itself is exercised by
//! tests/farm/slurm.sh).

use std::path::{Path, PathBuf};
use std::process::Command;

use crate::common::{glint, repo_file, stderr};

/// A copy of `shots/sphere_ops.ron` and its sphere in a folder whose name has a quote and a
/// space.
fn project() -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let root = dir.path().join("it's a shot");
    std::fs::create_dir_all(root.join("shots")).unwrap();
    std::fs::create_dir_all(root.join("patches")).unwrap();
    std::fs::copy(
        repo_file("patches/sphere.ron"),
        root.join("patches/sphere.ron"),
    )
    .unwrap();
    let shot = root.join("shots/sphere_ops.ron");
    std::fs::copy(repo_file("shots/sphere_ops.ron"), &shot).unwrap();
    (dir, shot)
}

fn script(shot: &Path, extra: &[&str]) -> String {
    let mut args = vec![
        "farm",
        "slurm",
        shot.to_str().unwrap(),
        "--frames",
        "1-30",
        "--chunk",
        "8",
    ];
    args.extend_from_slice(extra);
    let out = glint().args(&args).output().unwrap();
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    String::from_utf8(out.stdout).unwrap()
}

#[test]
fn the_script_cuts_the_frames_into_chunks_and_requeues_a_failed_task() {
    let (_dir, shot) = project();
    let text = script(
        &shot,
        &[
            "--cpus",
            "4",
            "--retries",
            "3",
            "--preset",
            "preview",
            "--size",
            "64x64",
        ],
    );
    assert!(text.starts_with("#!/bin/bash\n"), "{text}");
    for line in [
        "#SBATCH --array=0-3",
        "#SBATCH --cpus-per-task=4",
        "#SBATCH --requeue",
        "chunks=('1-8' '9-16' '17-24' '25-30')",
        "-lt 3 ]; then",
        "--skip-existing --size 64x64 --preset preview",
    ] {
        assert!(text.contains(line), "no {line:?} in\n{text}");
    }
    // The estimate for a 64×64 preview frame, and a quarter more (docs/limits.md: 64 MiB,
    // 90 B a sample, 200 B a vertex of the sphere's mesh, 4 × 2 spans of at most 64 segments
    // each).
    let mem = text
        .lines()
        .find_map(|l| l.strip_prefix("#SBATCH --mem="))
        .unwrap();
    let mib: u64 = mem.trim_end_matches('M').parse().unwrap();
    let image = (64u64 << 20) + 64 * 64 * 90;
    let most_mesh = (4 * 64 + 1) * (2 * 64 + 1) * 200;
    let requested = |bytes: u64| (bytes + bytes / 4).div_ceil(1 << 20);
    assert!(
        (requested(image + 9 * 5 * 200)..=requested(image + most_mesh)).contains(&mib),
        "{mem}"
    );
    // Each task may use what it requests, and no more.
    assert!(text.contains(&format!("--max-memory '{mem}'")), "{text}");
    let given = script(&shot, &["--mem", "6g"]);
    assert!(given.contains("#SBATCH --mem=6G"), "{given}");
    assert!(given.contains("--max-memory '6G'"), "{given}");
    let bare = script(&shot, &["--mem", "4000"]);
    assert!(bare.contains("--max-memory '4000M'"), "{bare}");
    assert!(
        given.contains("verify '\\''"),
        "the verification is printed, quoted: {given}"
    );
}

#[test]
fn a_task_of_the_script_renders_its_chunk() {
    let (dir, shot) = project();
    let text = script(&shot, &["--preset", "preview", "--size", "32x32"]);
    let file = dir.path().join("array.sh");
    std::fs::write(&file, &text).unwrap();
    let out = Command::new("bash")
        .arg(&file)
        .env("SLURM_ARRAY_TASK_ID", "1")
        .env("SLURM_ARRAY_JOB_ID", "7")
        .env("SLURM_CPUS_PER_TASK", "1")
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let frames = shot
        .parent()
        .unwrap()
        .parent()
        .unwrap()
        .join("out/sphere_ops");
    let mut written: Vec<String> = std::fs::read_dir(&frames)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    written.sort();
    let expected: Vec<String> = (9..=16).map(|f| format!("sphere_ops.{f:04}.png")).collect();
    assert_eq!(written, expected);
}

/// Runs task 1 of job 7 of the script `file` with `scontrol` answered by the stub in `stubs`,
/// after `restarts` earlier tries.
fn run_task(file: &Path, stubs: &Path, restarts: u32) -> std::process::Output {
    let path = format!(
        "{}:{}",
        stubs.display(),
        std::env::var("PATH").unwrap_or_default()
    );
    Command::new("bash")
        .arg(file)
        .env("PATH", path)
        .env("SLURM_ARRAY_TASK_ID", "1")
        .env("SLURM_ARRAY_JOB_ID", "7")
        .env("SLURM_CPUS_PER_TASK", "1")
        .env("SLURM_RESTART_COUNT", restarts.to_string())
        .output()
        .unwrap()
}

#[test]
fn a_failed_task_asks_slurm_to_requeue_it_and_ends_with_its_failure_when_refused() {
    use std::os::unix::fs::PermissionsExt;
    let (dir, shot) = project();
    let text = script(
        &shot,
        &["--preset", "preview", "--size", "32x32", "--retries", "2"],
    );
    let file = dir.path().join("array.sh");
    std::fs::write(&file, &text).unwrap();
    // The frames' folder cannot be made: a file stands where it goes.
    std::fs::write(shot.parent().unwrap().parent().unwrap().join("out"), "").unwrap();
    // An scontrol that writes down what it is asked and refuses it.
    let stubs = dir.path().join("bin");
    std::fs::create_dir(&stubs).unwrap();
    let asked = dir.path().join("asked.txt");
    let stub = stubs.join("scontrol");
    std::fs::write(
        &stub,
        format!(
            "#!/bin/bash\necho \"$@\" >> '{}'\nexit 1\n",
            asked.display()
        ),
    )
    .unwrap();
    std::fs::set_permissions(&stub, std::fs::Permissions::from_mode(0o755)).unwrap();

    let out = run_task(&file, &stubs, 1);
    let said = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(2), "{said}{}", stderr(&out));
    assert!(said.contains("task 1 failed (2): requeued"), "{said}");
    assert!(
        stderr(&out).contains("task 1 failed (2): Slurm did not requeue it"),
        "{}",
        stderr(&out)
    );
    assert_eq!(std::fs::read_to_string(&asked).unwrap(), "requeue 7_1\n");

    // Its last try: no requeue is asked for, and the task ends with the render's failure.
    let out = run_task(&file, &stubs, 2);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(!String::from_utf8_lossy(&out.stdout).contains("requeued"));
    assert_eq!(std::fs::read_to_string(&asked).unwrap(), "requeue 7_1\n");
}

#[test]
fn a_frame_larger_than_this_machine_takes_is_farmed_with_the_memory_it_asks_for() {
    let (_dir, shot) = project();
    // About 24 GB a frame: above the ceiling of a machine with less than 32 GB, which `render`
    // refuses here; a farm task's ceiling is what it requests of its node.
    let text = script(&shot, &["--size", "16384x16384", "--preset", "preview"]);
    let mem = text
        .lines()
        .find_map(|l| l.strip_prefix("#SBATCH --mem="))
        .unwrap();
    let mib: u64 = mem.trim_end_matches('M').parse().unwrap();
    let pixels = 16384u64 * 16384;
    // docs/limits.md: 64 MiB and 90 B a sample, and a quarter more.
    let least = (64u64 << 20) + pixels * 90;
    assert!(mib >= (least + least / 4) >> 20, "{mem}");
    assert!(text.contains(&format!("--max-memory '{mem}'")), "{text}");
}

#[test]
fn bad_options_are_refused_in_one_line() {
    let (_dir, shot) = project();
    for (flag, value) in [
        ("--mem", "lots"),
        ("--mem", "4GB"),
        ("--chunk", "0"),
        ("--cpus", "0"),
    ] {
        let out = glint()
            .args(["farm", "slurm", shot.to_str().unwrap(), flag, value])
            .output()
            .unwrap();
        assert_eq!(
            out.status.code(),
            Some(2),
            "{flag} {value}: {}",
            stderr(&out)
        );
    }
    let out = glint()
        .args(["farm", "slurm", "no/such/shot.ron"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(stderr(&out).lines().count(), 1, "{}", stderr(&out));
}
