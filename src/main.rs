/// With the explorer built in, every Rust allocation is counted (Rerun's accounting
/// allocator around the system one): the explorer reports the Rust heap apart from the
/// resident size, and the embedded viewer's memory limit applies to the data it holds rather
/// than to whatever the graphics driver keeps (a software Vulkan driver keeps a lot).
#[cfg(feature = "gui")]
#[global_allocator]
static ALLOCATOR: rerun::external::re_viewer::external::re_memory::AccountingAllocator<
    std::alloc::System,
> = rerun::external::re_viewer::external::re_memory::AccountingAllocator::new(std::alloc::System);

fn main() -> std::process::ExitCode {
    flexmodes::cli::main()
}
