#include "commands.h"

#include "studio_server.h"

#include <malloc.h>

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <thread>

namespace meander::cli {

namespace {

struct ServeArgs {
  std::string host = "127.0.0.1";
  int port = 8080;
  size_t max_upload = size_t(256) << 20;
  int64_t max_faces = StudioServerOptions{}.max_faces;
  int64_t max_pixels = StudioServerOptions{}.max_pixels;
  int64_t max_result = StudioServerOptions{}.max_result;
  bool open = false;
  std::filesystem::path page;
  bool test_hooks = false;
};

// The built page, found at run time beside the program: installed, PREFIX/bin/meander
// serves PREFIX/share/meander/studio; in a build tree, BUILD/meander serves
// BUILD/share/meander/studio, which the build copies from studio/dist. Empty (a notice
// in place of the page) when neither holds an index.html.
std::filesystem::path page_beside_program() {
  std::error_code error;
  const std::filesystem::path program = std::filesystem::read_symlink("/proc/self/exe", error);
  if (error) return {};
  for (const auto& page : {program.parent_path().parent_path() / "share/meander/studio",
                           program.parent_path() / "share/meander/studio"})
    if (std::filesystem::is_regular_file(page / "index.html", error)) return page;
  return {};
}

// Every update allocates the same large arrays again. glibc hands blocks of 128 KiB and
// more back to the kernel when they are freed, and on this kind of virtual machine a
// fresh page costs more than the work on it: a third of
// a preview's time went to zeroing pages. The server keeps up to 1 GiB of freed memory
// in one arena instead, so that the next update, on any thread, reuses it; no block is
// mapped on its own (which glibc does past 32 MiB whatever the threshold), so that a
// 40 MB view is reused too.
void keep_freed_memory() {
  mallopt(M_ARENA_MAX, 1);
  mallopt(M_MMAP_MAX, 0);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
}

void run_serve(const ServeArgs& a) {
  keep_freed_memory();
  StudioServer server({.host = a.host,
                       .port = a.port,
                       .max_upload = a.max_upload,
                       .page = a.page.empty() ? page_beside_program() : a.page,
                       .max_faces = a.max_faces,
                       .max_pixels = a.max_pixels,
                       .max_result = a.max_result,
                       .test_hooks = a.test_hooks});
  const int port = server.bind();
  const std::string url = "http://" + (a.host.find(':') != std::string::npos ? "[" + a.host + "]" : a.host) + ":" +
                          std::to_string(port) + "/";
  std::printf("Meander studio: %s\n", url.c_str());
  std::fflush(stdout);
  if (a.open) {
    // The URL is ours (host and number), so no shell quoting question arises.
    const std::string command = "xdg-open '" + url + "' > /dev/null 2>&1 &";
    if (std::system(command.c_str()) != 0) std::fprintf(stderr, "meander serve: could not open a browser; visit %s\n", url.c_str());
  }
  // Ctrl-C and SIGTERM stop the server cleanly.
  sigset_t stop_signals;
  sigemptyset(&stop_signals);
  sigaddset(&stop_signals, SIGINT);
  sigaddset(&stop_signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &stop_signals, nullptr);
  std::thread waiter([&] {
    int signal = 0;
    sigwait(&stop_signals, &signal);
    server.stop();
  });
  server.run();
  // run() also ends if listening fails; wake the waiter so it can be joined.
  pthread_kill(waiter.native_handle(), SIGTERM);
  waiter.join();
}

} // namespace

Command add_serve_command(CLI::App& parent) {
  auto args = std::make_shared<ServeArgs>();
  CLI::App* app = parent.add_subcommand("serve", "Start the studio: a local web page to make curves and wires interactively");
  app->add_option("--port", args->port, "TCP port (0: any free port)")->check(CLI::Range(0, 65535))->capture_default_str();
  app->add_option("--host", args->host, "address to listen on (127.0.0.1: this machine only)")->capture_default_str();
  app->add_option("--max-upload", args->max_upload, "largest request body in bytes (bigger uploads get HTTP 413)")
      ->check(CLI::PositiveNumber)->capture_default_str();
  app->add_option("--max-faces", args->max_faces, "largest mesh in faces (bigger uploads get HTTP 422)")
      ->check(CLI::PositiveNumber)->capture_default_str();
  app->add_option("--max-pixels", args->max_pixels, "largest picture in pixels (bigger uploads get HTTP 422)")
      ->check(CLI::PositiveNumber)->capture_default_str();
  app->add_option("--max-result", args->max_result,
                  "largest result in curve points, triangles and texture pixels (bigger requests get HTTP 413)")
      ->check(CLI::PositiveNumber)->capture_default_str();
  app->add_flag("--open", args->open, "open the page in the default browser");
  app->add_option("--page", args->page,
                  "folder of the built page (default: share/meander/studio beside the program, as installed or built)")
      ->check(CLI::ExistingDirectory);
  // Not in --help: for the studio's browser test (StudioServerOptions::test_hooks).
  app->add_flag("--test-hooks", args->test_hooks, "let make requests hold their job until cancelled")->group("");
  return {app, [args] { run_serve(*args); }};
}

} // namespace meander::cli
