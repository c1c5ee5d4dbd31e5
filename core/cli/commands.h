// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once

#include <string>
#include <vector>

namespace tinlod::cli {

// Each command takes the arguments after its name and returns the exit code;
// failures are thrown as tinlod::Error and reported once by main().
int sampleCommand(std::vector<std::string> args);
int buildCommand(std::vector<std::string> args);
int infoCommand(std::vector<std::string> args);
int insertCommand(std::vector<std::string> args);
int lodCommand(std::vector<std::string> args);
int linesCommand(std::vector<std::string> args);
int locateCommand(std::vector<std::string> args);
int accuracyCommand(std::vector<std::string> args);
int experimentCommand(std::vector<std::string> args);
int makeDemCommand(std::vector<std::string> args);
// Never returns but with an error: it runs tinlod-tiles in this process's place.
int tilesCommand(std::vector<std::string> args);

}  // namespace tinlod::cli
