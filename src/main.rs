fn main() -> std::process::ExitCode {
    flexmodes::cli::main()
}
