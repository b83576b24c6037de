// Scene files and text in, checked SceneDefs out.
#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <system_error>

#include "scene.pb.h"
#include "scene/scene.h"
#include "scene_checker.h"
#include "text_parser.h"

namespace scene {

namespace {

SceneError file_error(const std::filesystem::path& path, std::string message) {
  SceneError error;
  error.file = path.string();
  error.message = std::move(message);
  return error;
}

}  // namespace

SceneResult parse_scene_text(std::string_view text, std::string_view origin) {
  physics::scene::Scene message;
  google::protobuf::TextFormat::ParseInfoTree locations;
  if (auto error = detail::parse_text(text, origin, &message, &locations)) return *error;
  return detail::check_scene(message, origin, locations);
}

SceneResult load_scene_file(const std::filesystem::path& path) {
  std::error_code code;
  const std::filesystem::file_status status = std::filesystem::status(path, code);
  if (code || !std::filesystem::exists(status))
    return file_error(path, "cannot open the scene file: " +
                                (code ? code.message() : std::string("no such file")));
  // Only regular files: a directory or a device (/dev/zero) has no useful size.
  if (!std::filesystem::is_regular_file(status)) return file_error(path, "not a regular file");
  const std::uintmax_t size = std::filesystem::file_size(path, code);
  if (code) return file_error(path, "cannot read the scene file size: " + code.message());
  if (size > kMaxSceneFileBytes)
    return file_error(
        path, "the scene file has " + std::to_string(size) + " bytes, more than the limit of " +
                  std::to_string(kMaxSceneFileBytes) + " (use grids for large scenes)");
  std::ifstream in(path, std::ios::binary);
  if (!in)
    return file_error(path, std::string("cannot open the scene file: ") + std::strerror(errno));
  std::string text;
  text.resize(static_cast<std::size_t>(size));
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  // The file may have shrunk since its size was read; keep what was there.
  text.resize(static_cast<std::size_t>(in.gcount()));
  if (in.bad()) return file_error(path, "cannot read the scene file");
  if (text.empty()) return file_error(path, "the scene file is empty");
  return parse_scene_text(text, path.string());
}

}  // namespace scene
