#include "shaders_cpp/image_io/atomic_file.h"

#include <unistd.h>

#include <filesystem>

namespace tessera {

std::string write_atomically(const std::string& path, const std::function<std::string(const std::string&)>& write) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  if (!fs::is_directory(dir)) return path + ": directory '" + dir.string() + "' does not exist";
  std::string name = ".";
  name.append(target.stem().string())
      .append(".tmp")
      .append(std::to_string(::getpid()))
      .append(target.extension().string());
  const fs::path temp = dir / name;
  std::error_code ec;
  if (std::string error = write(temp.string()); !error.empty()) {
    fs::remove(temp, ec);
    return error;
  }
  fs::rename(temp, target, ec);
  if (ec) {
    std::error_code ignored;
    fs::remove(temp, ignored);
    return path + ": cannot rename the finished file into place: " + ec.message();
  }
  return {};
}

}  // namespace tessera
