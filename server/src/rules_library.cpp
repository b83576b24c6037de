#include "server/rules_library.h"

#include <dlfcn.h>

#include <cstring>
#include <exception>
#include <string>
#include <system_error>
#include <utility>

#include "server/rules_plugin.h"

namespace server {

namespace {

// The library's handle, closed once the rules made by it are gone (their code and
// destructor live in it).
class LibraryHandle {
 public:
  explicit LibraryHandle(void* handle) : handle_(handle) {}
  ~LibraryHandle() {
    if (handle_ != nullptr) dlclose(handle_);
  }
  LibraryHandle(const LibraryHandle&) = delete;
  LibraryHandle& operator=(const LibraryHandle&) = delete;
  void* get() const { return handle_; }

 private:
  void* handle_;
};

// The rules and the library they came from; members are destroyed in reverse order,
// so the rules go before the library is closed.
struct RulesInLibrary {
  std::shared_ptr<LibraryHandle> library;
  std::shared_ptr<GameRules> rules;
};

LoadedRules failure(const std::filesystem::path& file, const std::string& why) {
  return {nullptr, "rules library " + file.string() + ": " + why};
}

std::string dl_error() {
  const char* text = dlerror();
  return text != nullptr ? text : "unknown error";
}

// Empty when the library was built for this server, otherwise why not.
std::string check_build(const RulesPluginInfo& info) {
  if (info.plugin_abi != PHYSICS_RULES_PLUGIN_ABI) {
    return "built for rules plugin ABI " + std::to_string(info.plugin_abi) +
           ", this physics-server loads ABI " + std::to_string(PHYSICS_RULES_PLUGIN_ABI) +
           ": rebuild it against physics_server " PHYSICS_SERVER_VERSION;
  }
  const char* version = info.package_version != nullptr ? info.package_version : "(none)";
  if (std::strcmp(version, PHYSICS_SERVER_VERSION) != 0) {
    return std::string("built against physics_server ") + version +
           ", this physics-server is " PHYSICS_SERVER_VERSION
           ": rebuild it against physics_server " PHYSICS_SERVER_VERSION;
  }
  const char* stdlib = info.standard_library != nullptr ? info.standard_library : "(none)";
  if (std::strcmp(stdlib, PHYSICS_RULES_STDLIB) != 0) {
    return std::string("built with the C++ standard library ") + stdlib +
           ", this physics-server with " PHYSICS_RULES_STDLIB;
  }
  if (info.make_rules == nullptr) return "its entry point names no rules factory";
  return {};
}

}  // namespace

LoadedRules load_rules_library(const std::filesystem::path& file, const scene::SceneDef& scene) {
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) return failure(file, "no such file");
  if (!std::filesystem::is_regular_file(file, ec)) return failure(file, "not a regular file");
  // An absolute path: dlopen searches the library path for a bare name instead.
  const std::filesystem::path path = std::filesystem::absolute(file, ec);
  dlerror();
  auto library = std::make_shared<LibraryHandle>(dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL));
  if (library->get() == nullptr) {
    return failure(file, "the dynamic loader cannot load it: " + dl_error());
  }
  dlerror();
  void* symbol = dlsym(library->get(), PHYSICS_GAME_RULES_ENTRY_POINT);
  if (symbol == nullptr) {
    return failure(file, "no entry point " PHYSICS_GAME_RULES_ENTRY_POINT
                         " (define it with PHYSICS_GAME_RULES, server/rules_plugin.h)");
  }
  using EntryPoint = const RulesPluginInfo* (*)();
  const RulesPluginInfo* info = reinterpret_cast<EntryPoint>(symbol)();
  if (info == nullptr) return failure(file, "its entry point returned nothing");
  if (const std::string why = check_build(*info); !why.empty()) return failure(file, why);

  auto held = std::make_shared<RulesInLibrary>();
  held->library = std::move(library);
  try {
    held->rules = info->make_rules(scene);
  } catch (const std::exception& error) {
    return failure(file, std::string("its rules factory threw: ") + error.what());
  } catch (...) {
    return failure(file, "its rules factory threw something other than a std::exception");
  }
  if (!held->rules) return failure(file, "its rules factory made no rules (a null pointer)");
  GameRules* rules = held->rules.get();
  // The rules as the caller sees them, keeping the library loaded while they live.
  return {std::shared_ptr<GameRules>(std::move(held), rules), {}};
}

}  // namespace server
