// The HTTP side of `tessera view` (cpp-httplib): the page and its HTTP API over a ViewerSession.
//
// API (GET only; settings in the query, named like `tessera render`'s options without the dashes,
// viewer_settings.h; errors are a status and one line of text/plain):
//   /                      the page (viewer_page.html, viewer.js, viewer.css, compiled in)
//   /api/info              JSON: the asset, its animations and bounds, the framing camera, the views,
//                          the starting settings and the names a request may set
//   /api/frame?SETTINGS    the frame: image/png, or image/jpeg with format=jpeg; the render summary
//                          (render --json's) in the X-Tessera-Summary header. With client=ID&seq=N, a
//                          request still waiting when a later seq of the same client arrives gets
//                          409 (superseded) instead of a frame.
//   /api/pick?x=X&y=Y&SETTINGS   JSON: the patch under pixel (X, Y), its --stats row, or null
//   /api/command?SETTINGS  JSON: the reproducing `tessera render` command and the scene file
// 400 for a bad setting or request, 404 for any other path, 500 for a failure of the render itself.
// No part of a request names a file: the server reads only the asset it was started with.
#pragma once

#include <memory>
#include <string>

#include "tools/viewer/viewer_session.h"

namespace tessera::viewer {

class ViewerServer {
 public:
  explicit ViewerServer(ViewerSession& session);
  ~ViewerServer();
  ViewerServer(const ViewerServer&) = delete;
  ViewerServer& operator=(const ViewerServer&) = delete;

  // Binds `host`:`port` (port 0: any free port) and returns the port; InputError when it cannot.
  int bind(const std::string& host, int port);
  // Serves until stop() (from any thread). Returns false when serving failed.
  bool serve();
  void stop();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The page's files, compiled in (viewer_assets.cpp, generated from tools/viewer/page/).
extern const char* const kViewerPageHtml;
extern const char* const kViewerPageJs;
extern const char* const kViewerPageCss;

}  // namespace tessera::viewer
