#include "tools/viewer/viewer_server.h"

#include <httplib.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>

#include "tools/scene/common.h"

namespace tessera::viewer {

using namespace scene;

namespace {

// One line of text/plain with `status`, for every error a request can get.
void fail(httplib::Response& res, int status, const std::string& message) {
  res.status = status;
  res.set_content(one_line_message(message) + "\n", "text/plain; charset=utf-8");
}

QueryParams query_of(const httplib::Request& req) {
  QueryParams q;
  for (const auto& [name, value] : req.params) q.emplace_back(name, value);
  return q;
}

int integer_param(const httplib::Request& req, const char* name) {
  if (!req.has_param(name)) throw RequestError(std::string(name) + ": missing");
  const std::string v = req.get_param_value(name);
  std::size_t used = 0;
  long long n = 0;
  try {
    n = std::stoll(v, &used);
  } catch (const std::logic_error&) {
    used = 0;
  }
  if (used == 0 || used != v.size() || n < -1000000000LL || n > 1000000000LL)
    throw RequestError(std::string(name) + ": '" + v.substr(0, 40) + "' is not an integer");
  return int(n);
}

}  // namespace

struct ViewerServer::Impl {
  ViewerSession& session;
  httplib::Server http;
  std::mutex seq_mutex;
  // Per client: the newest frame asked for, and when the client last asked (a tick). At most
  // kMaxClients are kept, the longest silent dropped first: client IDs come from requests, and a map
  // that grew with each new ID would let any caller grow the server's memory without bound.
  static constexpr std::size_t kMaxClients = 256;
  struct ClientSeq {
    long long seq = 0;
    std::uint64_t tick = 0;
  };
  std::map<std::string, ClientSeq> latest_seq;
  std::uint64_t ticks = 0;

  // Records `seq` for `client` (under seq_mutex).
  void note_seq(const std::string& client, long long seq) {
    auto it = latest_seq.find(client);
    if (it == latest_seq.end()) {
      if (latest_seq.size() >= kMaxClients)
        latest_seq.erase(std::min_element(latest_seq.begin(), latest_seq.end(),
                                          [](const auto& a, const auto& b) { return a.second.tick < b.second.tick; }));
      it = latest_seq.emplace(client, ClientSeq{seq, 0}).first;
    }
    it->second.seq = std::max(it->second.seq, seq);
    it->second.tick = ++ticks;
  }

  explicit Impl(ViewerSession& s) : session(s) { routes(); }

  // Runs `body`, turning the session's errors into HTTP statuses.
  template <class Body>
  void guarded(const httplib::Request& req, httplib::Response& res, Body&& body) {
    const auto start = std::chrono::steady_clock::now();
    try {
      body();
    } catch (const RequestError& e) {
      fail(res, 400, e.what());
    } catch (const UsageError& e) {
      fail(res, 400, e.what());
    } catch (const InputError& e) {
      // Settings this asset cannot take (a scheme that cannot draw its faces or be displaced): the
      // request is well formed, the asset refuses it. The message is the CLI's.
      fail(res, 422, e.what());
    } catch (const std::exception& e) {
      fail(res, 500, e.what());
    }
    log_debug("view: " + req.path + " " + std::to_string(res.status) + " in " +
              float_text(float(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() * 1e3)) +
              " ms");
  }

  RenderSettings settings(const httplib::Request& req) {
    for (const auto& [name, value] : req.params) {
      (void)value;
      if (req.get_param_value_count(name) > 1) throw RequestError("'" + name + "' is given twice");
    }
    return settings_from_query(session.base(), query_of(req));
  }

  void routes() {
    const auto page = [](const char* body, const char* type) {
      return [body, type](const httplib::Request&, httplib::Response& res) {
        res.set_header("Cache-Control", "no-store");
        res.set_content(body, type);
      };
    };
    http.Get("/", page(kViewerPageHtml, "text/html; charset=utf-8"));
    http.Get("/viewer.js", page(kViewerPageJs, "text/javascript; charset=utf-8"));
    http.Get("/viewer.css", page(kViewerPageCss, "text/css; charset=utf-8"));
    http.Get("/api/info", [this](const httplib::Request& req, httplib::Response& res) {
      guarded(req, res, [&] { res.set_content(json_text(session.info()), "application/json"); });
    });
    http.Get("/api/frame", [this](const httplib::Request& req, httplib::Response& res) {
      guarded(req, res, [&] { frame(req, res); });
    });
    // Not serialised with the frames: a page polls it while its frame is being prepared.
    http.Get("/api/progress", [this](const httplib::Request& req, httplib::Response& res) {
      guarded(req, res, [&] {
        res.set_header("Cache-Control", "no-store");
        res.set_content(json_text(session.progress()), "application/json");
      });
    });
    http.Get("/api/pick", [this](const httplib::Request& req, httplib::Response& res) {
      guarded(req, res, [&] {
        const RenderSettings s = settings(req);
        const Json j = session.pick(s, integer_param(req, "x"), integer_param(req, "y"));
        res.set_content(json_text(j), "application/json");
      });
    });
    http.Get("/api/command", [this](const httplib::Request& req, httplib::Response& res) {
      guarded(req, res, [&] { res.set_content(json_text(session.command(settings(req))), "application/json"); });
    });
    // Anything else: one line naming what was asked.
    http.set_error_handler([](const httplib::Request& req, httplib::Response& res) {
      if (res.status == 404)
        fail(res, 404, req.method + " " + req.path.substr(0, 80) + ": not part of the viewer (see GET /api/info)");
      else if (res.body.empty())
        fail(res, res.status, "the request was refused (HTTP " + std::to_string(res.status) + ")");
    });
    http.set_exception_handler([](const httplib::Request&, httplib::Response& res, std::exception_ptr) {
      fail(res, 500, "the server failed on this request");
    });
  }

  void frame(const httplib::Request& req, httplib::Response& res) {
    const RenderSettings s = settings(req);
    FrameFormat format = FrameFormat::png;
    if (req.has_param("format")) {
      const std::string f = req.get_param_value("format");
      if (f == "jpeg" || f == "jpg")
        format = FrameFormat::jpeg;
      else if (f != "png")
        throw RequestError("format: '" + f.substr(0, 40) + "' is not png or jpeg");
    }
    std::function<bool()> wanted;
    if (req.has_param("client")) {
      const std::string client = req.get_param_value("client");
      if (client.empty() || client.size() > 64) throw RequestError("client: expected 1 to 64 characters");
      const long long seq = integer_param(req, "seq");
      {
        std::lock_guard lock(seq_mutex);
        note_seq(client, seq);
      }
      wanted = [this, client, seq] {
        std::lock_guard lock(seq_mutex);
        const auto it = latest_seq.find(client);  // a dropped client's request is still wanted
        return it == latest_seq.end() || it->second.seq <= seq;
      };
    }
    const std::optional<ViewerFrame> f = session.frame(s, format, wanted);
    if (!f) {
      fail(res, 409, "superseded: a later frame of this client was asked for");
      return;
    }
    res.set_header("Cache-Control", "no-store");
    res.set_header("X-Tessera-Summary", json_text(f->summary));
    res.set_content(f->bytes, f->content_type);
  }
};

ViewerServer::ViewerServer(ViewerSession& session) : impl_(std::make_unique<Impl>(session)) {}
ViewerServer::~ViewerServer() = default;

int ViewerServer::bind(const std::string& host, int port) {
  if (port < 0 || port > 65535) throw UsageError("--port: " + std::to_string(port) + " is not in 0..65535");
  const int bound = port == 0 ? impl_->http.bind_to_any_port(host) : (impl_->http.bind_to_port(host, port) ? port : -1);
  if (bound < 0)
    throw InputError("cannot listen on " + host + ":" + std::to_string(port) +
                     " (in use, or not an address of this machine)");
  return bound;
}

bool ViewerServer::serve() { return impl_->http.listen_after_bind(); }

void ViewerServer::stop() { impl_->http.stop(); }

}  // namespace tessera::viewer
