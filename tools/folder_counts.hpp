#pragma once
/// What a stand folder's report.json counted against the tables read back: organs.csv cut at a
/// line end (a copy or sync stopped short) reads as a smaller stand without an error, so readers
/// (canopy detect, render, light, Stand.read) say where the two disagree.
#include "geometry/staged_folder.hpp"
#include "geometry/stand.hpp"

#include <string>
#include <vector>

namespace canopy::cli {

/// Notes for a stand read from `dir` whose plants or organs differ from the counts of the
/// folder's report.json (none where there is no report, as Stand.export writes none, or where it
/// holds no counts). A note, not an error: a table edited on purpose is the user's to read.
/// `before`: folder_identity(dir, "organs.csv") taken before the stand was read; where the folder
/// is another by the time its report is read (a run replaced it meanwhile), the report is of
/// another stand and nothing is said.
std::vector<std::string> folder_count_notes(const std::string& dir, const Stand& stand,
                                            const FolderIdentity& before);

}  // namespace canopy::cli
