use clap::Parser;

fn main() {
    let cli = rodnet::cli::Cli::parse();
    std::process::exit(rodnet::cli::run(cli));
}
