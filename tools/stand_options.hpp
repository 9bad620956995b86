#pragma once
/// canopy stand's options that grow a stand and choose its files, registered alike by every command
/// that grows one from a grammar (stand, light, render): the same names, checks and help, and a
/// command given a folder instead of a grammar refuses the options that would have grown one.
#include "tools/stand_run.hpp"

#include <CLI/CLI.hpp>

#include <initializer_list>
#include <string>
#include <string_view>

namespace canopy::cli {

/// The help's groups, and what refuse_given() tells apart.
inline constexpr const char* kGrowGroup = "Growing a stand";
inline constexpr const char* kLayoutGroup = "Layout";
inline constexpr const char* kFilesGroup = "Stand files";
inline constexpr const char* kDetectGroup = "Detection";
inline constexpr const char* kResolveGroup = "Resolution";

/// Options added to `app` while one lives go to help group `name`.
class OptionGroup {
 public:
  OptionGroup(CLI::App& app, std::string name);
  ~OptionGroup();
  OptionGroup(const OptionGroup&) = delete;
  OptionGroup& operator=(const OptionGroup&) = delete;

 private:
  CLI::App& app_;
  std::string before_;
};

/// --steps, --set, --lod, --max-modules, --any-grammar-path, the target options, and the layout
/// (rows, or --positions) as an option group. `prefix` starts each description ("From a grammar: "
/// where SOURCE may also be a folder).
void add_grow_options(CLI::App& app, StandOptions& s, const std::string& prefix = "");
/// --formats, --glb-instancing, --glb-compact.
void add_file_options(CLI::App& app, StandOptions& s, const std::string& prefix = "");

/// Throws std::invalid_argument "OPTION: `reason`" naming the first option of `groups` (those in
/// `except` aside) given on the command line: options a run would ignore (SOURCE a folder that
/// holds its stand already; Python's Stand.light on the stand it holds).
void refuse_given(const CLI::App& app, std::initializer_list<std::string_view> groups,
                  std::initializer_list<std::string_view> except, const std::string& reason);

/// refuse_given's reason where SOURCE `folder` holds a stand (canopy light DIR, canopy render DIR).
std::string holds_a_stand(const std::string& folder);

/// `canopy stand`'s arguments and options registered on `app` (the subcommand, or an app of its
/// own for the Python module, which parses its keywords with it).
std::shared_ptr<StandOptions> register_stand(CLI::App& app);

}  // namespace canopy::cli
