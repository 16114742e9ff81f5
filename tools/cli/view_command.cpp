// `tessera view CAGE [render options] [--port N] [--bind ADDR]`: the asset in the browser, served on
// 127.0.0.1 (tools/viewer/): orbit, change the factors, LOD, scheme and view, pick a patch, and copy
// the `tessera render` command that reproduces the frame on screen. Prints the URL on stdout and
// serves until Ctrl-C (SIGINT) or SIGTERM, then exits 0.
#include <pthread.h>
#include <signal.h>

#include <atomic>
#include <ctime>
#include <iostream>
#include <thread>

#include "tools/cli/commands.h"
#include "tools/cli/progress.h"
#include "tools/scene/common.h"
#include "tools/scene/scene_file.h"
#include "tools/viewer/viewer_server.h"

namespace tessera::cli {

using namespace scene;
using namespace viewer;

namespace {

struct ViewOptions {
  RenderSettings s;
  std::string scene, bind = "127.0.0.1";
  int port = 8080;
};

int run_view(const ViewOptions& given, const CLI::App& cmd) {
  RenderSettings s = given.s;
  if (!given.scene.empty()) {
    if (!s.cage.empty()) throw UsageError("a cage and --scene: the scene names its asset");
    for (const CLI::Option* opt : cmd.get_options()) {
      const std::string name = opt->get_name();
      if (opt->count() > 0 && name != "--scene" && name != "--port" && name != "--bind" && name != "--threads")
        throw UsageError(name + " with --scene: the scene sets it (edit the scene; the page changes it live)");
    }
    const int threads = s.threads;
    s = read_scene(given.scene);
    if (cmd.count("--threads") > 0) s.threads = threads;
  }
  if (s.cage.empty()) throw UsageError("give a cage, or --scene FILE");
  // SIGINT and SIGTERM are taken by one thread (below), not by whichever thread they land on: blocked
  // here, before any thread starts, so every thread inherits the mask.
  sigset_t stop_signals;
  sigemptyset(&stop_signals);
  sigaddset(&stop_signals, SIGINT);
  sigaddset(&stop_signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &stop_signals, nullptr);

  StepProgress preparing("preparing " + s.cage);
  ViewerSession session(s, preparing.hook());
  preparing.finish();
  // Settings the renderer refuses fail here, at start, rather than in the first request.
  session.frame(s, FrameFormat::png);
  ViewerServer server(session);
  const int port = server.bind(given.bind, given.port);
  const std::string host = given.bind.find(':') != std::string::npos ? "[" + given.bind + "]" : given.bind;
  const std::string url = "http://" + host + ":" + std::to_string(port) + "/";
  std::cout << url << std::endl;
  log_info("view: serving " + s.cage + " at " + url + " (Ctrl-C stops)");
  if (given.bind != "127.0.0.1" && given.bind != "localhost" && given.bind != "::1")
    log_info("view: --bind " + given.bind + " serves this machine's files' renders to other machines");

  std::atomic<bool> done{false};
  int received = 0;
  std::thread waiter([&] {
    const timespec tick{0, 200'000'000};
    while (!done) {
      const int sig = sigtimedwait(&stop_signals, nullptr, &tick);
      if (sig == SIGINT || sig == SIGTERM) {
        received = sig;
        server.stop();
        return;
      }
    }
  });
  const bool served = server.serve();
  done = true;
  waiter.join();
  if (received != 0) {
    log_info(std::string("view: stopped (") + (received == SIGINT ? "SIGINT" : "SIGTERM") + ")");
    return kExitOk;
  }
  if (!served) throw InputError("view: serving " + url + " failed");
  return kExitOk;
}

}  // namespace

Runner add_view_command(CLI::App& app) {
  auto o = std::make_shared<ViewOptions>();
  CLI::App* cmd = app.add_subcommand(
      "view", "interactive tessellation debugging in the browser: serves the asset's frames on 127.0.0.1");
  cmd->add_option("cage", o->s.cage, "the cage: OBJ (OpenSubdiv tags allowed) or glTF (.gltf, .glb); or --scene");
  o->s.camera.width = 1280;
  o->s.camera.height = 720;
  add_settings_options(*cmd, o->s, PatchCullMode::all);
  cmd->add_option("--scene", o->scene, "start from the scene file FILE (the page can change its settings)");
  cmd->add_option("--port", o->port, "TCP port (0: any free port; the URL is printed)")->capture_default_str();
  cmd->add_option("--bind", o->bind,
                  "address to listen on; the default serves this machine only (0.0.0.0 opens it to the network)")
      ->capture_default_str();
  return [o, cmd] { return run_view(*o, *cmd); };
}

}  // namespace tessera::cli
