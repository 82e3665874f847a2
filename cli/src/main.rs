fn main() -> std::process::ExitCode {
    glint_cli::main()
}
