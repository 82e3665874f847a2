/// Frames allocate and free large per-pixel buffers; mimalloc keeps that memory for the next
/// frame instead of returning it to the system and faulting it back in.
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn main() -> std::process::ExitCode {
    glint::cli::main()
}
