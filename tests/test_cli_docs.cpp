// docs/cli.md against the programs' own help: the page shows each command's
// `--help` text in a fenced block under the command's heading, and this test
// holds every block to the live text, so a command, option or wording
// changed in the code without the page (or the page without the code) fails.
#include <gtest/gtest.h>

#include <fstream>
#include <optional>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cli_helpers.h"

namespace quadra {
namespace {

std::vector<std::string> docLines() {
  std::ifstream in(QUADRA_CLI_DOC);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// The title of a heading line ("## quadra render" -> "quadra render"), or "".
std::string headingTitle(const std::string& line) {
  const std::size_t hashes = line.find_first_not_of('#');
  if (hashes == 0 || hashes == std::string::npos || line[hashes] != ' ') return "";
  return line.substr(hashes + 1);
}

// The first fenced block under the heading `title`, each line ending in
// '\n' as the program prints it; nullopt when the heading or the block is
// missing (the block must come before the next heading).
std::optional<std::string> helpBlock(const std::vector<std::string>& lines,
                                     const std::string& title) {
  std::size_t i = 0;
  while (i < lines.size() && headingTitle(lines[i]) != title) ++i;
  for (++i; i < lines.size() && headingTitle(lines[i]).empty(); ++i) {
    if (lines[i].rfind("```", 0) != 0) continue;
    std::string block;
    for (++i; i < lines.size() && lines[i].rfind("```", 0) != 0; ++i) block += lines[i] + "\n";
    return block;
  }
  return std::nullopt;
}

// The options a help text lists: each "--name" that starts an option line
// (after the indentation) or follows one on it ("--width W --height H").
std::set<std::string> listedOptions(const std::string& help) {
  static const std::regex option("(^|\\s|\\[)(--[a-z][a-z0-9-]*)");
  std::set<std::string> names;
  std::istringstream lines(help);
  for (std::string line; std::getline(lines, line);) {
    const std::size_t first = line.find_first_not_of(' ');
    if (first == std::string::npos || line.compare(first, 2, "--") != 0) continue;
    for (std::sregex_iterator m(line.begin(), line.end(), option), end; m != end; ++m)
      names.insert((*m)[2].str());
  }
  return names;
}

std::string joined(const std::set<std::string>& names) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : ", ") + name;
  return text;
}

struct HelpText {
  std::string title;    // the heading in docs/cli.md
  std::string command;  // what prints it
  RunResult live;       // its output
};

std::vector<HelpText> everyHelpText() {
  std::vector<HelpText> texts = {{"quadra help", "quadra help", run("help")},
                                 {"quadra report", "quadra report --help", run("report --help")}};
  for (const std::string& command : commandsInOverview(texts[0].live.out))
    texts.push_back(
        {"quadra " + command, "quadra " + command + " --help", run(command + " --help")});
#ifdef QUADRA_LLVMPIPE_PATH
  texts.push_back({"quadra-llvmpipe render", "quadra-llvmpipe render --help",
                   runProgram(QUADRA_LLVMPIPE_PATH, "render --help")});
#endif
  return texts;
}

TEST(CliDocs, EveryHelpTextIsInDocsCliMdAsPrinted) {
  const std::vector<std::string> lines = docLines();
  ASSERT_FALSE(lines.empty()) << "cannot read " << QUADRA_CLI_DOC;
  for (const HelpText& text : everyHelpText()) {
    SCOPED_TRACE(text.title);
    ASSERT_EQ(text.live.exitCode, 0) << text.live.err;
    const std::optional<std::string> documented = helpBlock(lines, text.title);
    ASSERT_TRUE(documented) << QUADRA_CLI_DOC << " has no section '" << text.title
                            << "' with the help text in a fenced block: add one";
    const std::set<std::string> live = listedOptions(text.live.out),
                                doc = listedOptions(*documented);
    std::set<std::string> undocumented, gone;
    for (const std::string& name : live)
      if (!doc.count(name)) undocumented.insert(name);
    for (const std::string& name : doc)
      if (!live.count(name)) gone.insert(name);
    EXPECT_TRUE(undocumented.empty()) << "options the program takes that " << QUADRA_CLI_DOC << " '"
                                      << text.title << "' does not list: " << joined(undocumented);
    EXPECT_TRUE(gone.empty()) << "options " << QUADRA_CLI_DOC << " '" << text.title
                              << "' lists that the program does not take: " << joined(gone);
    if (*documented == text.live.out) continue;
    // The first line that differs, not two pages of text.
    std::istringstream docText(*documented), liveText(text.live.out);
    std::string docLine, liveLine;
    int line = 1;
    while (std::getline(docText, docLine) && std::getline(liveText, liveLine) &&
           docLine == liveLine)
      ++line;
    ADD_FAILURE() << "the help text changed: paste the output of `" << text.command
                  << "` into the fenced block under '" << text.title << "' in " << QUADRA_CLI_DOC
                  << " (and say in the prose there what changed for users); "
                  << "line " << line << " of the block differs:\n  page:    " << docLine
                  << "\n  program: " << liveLine;
  }
}

// A page section for a command that no longer exists fails too.
TEST(CliDocs, EveryCommandSectionOfDocsCliMdIsALiveCommand) {
  std::set<std::string> live;
  for (const HelpText& text : everyHelpText()) live.insert(text.title);
  for (const std::string& line : docLines()) {
    const std::string title = headingTitle(line);
    if (title.rfind("quadra ", 0) != 0 && title.rfind("quadra-llvmpipe ", 0) != 0) continue;
#ifndef QUADRA_LLVMPIPE_PATH
    if (title.rfind("quadra-llvmpipe ", 0) == 0) continue;  // not built here
#endif
    EXPECT_TRUE(live.count(title)) << QUADRA_CLI_DOC << " has a section '" << title
                                   << "', which is no command quadra lists: remove or rename it";
  }
}

}  // namespace
}  // namespace quadra
