#include "gcode/cli/completion.hpp"

#include <algorithm>
#include <string_view>

namespace gcode::cli {

namespace {

bool plain_word(std::string_view item) {
  return !item.empty() && std::all_of(item.begin(), item.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' || c == '_' ||
           c == '.' || c == '@';
  });
}

// The words of `list` between `separator`s, if every one is a plain word.
std::vector<std::string> words_of(std::string_view list, char separator) {
  std::vector<std::string> out;
  while (!list.empty()) {
    std::size_t end = std::min(list.find(separator), list.size());
    std::string_view item = list.substr(0, end);
    if (!plain_word(item)) return {};
    out.emplace_back(item);
    list.remove_prefix(std::min(list.size(), end + 1));
  }
  return out;
}

// Values that name a file: FILE, FILE[:LAYERS], PATH, IMAGE, DIR, STL, GCODE (a file or text) ...
bool names_file(std::string_view type) {
  for (const char* word : {"FILE", "PATH", "DIR", "IMAGE", "PICTURE", "STL", "LOG", "GCODE"})
    if (type.find(word) != std::string_view::npos) return true;
  return false;
}

// The values an option lists: "MODE:{auto,relative,absolute}" (what
// CLI::IsMember adds to the type name), or a type name that is the list
// itself, "x|y|z|cylinder|sphere", where a file may be one alternative:
// "PATH|virtual[:OPTS]" lists "virtual" (and the file names).
std::vector<std::string> listed_choices(const std::string& type) {
  std::size_t open = type.find('{');
  std::size_t close = type.find('}', open);
  if (open != std::string::npos && close != std::string::npos)
    return words_of(std::string_view(type).substr(open + 1, close - open - 1), ',');
  std::vector<std::string> words;
  bool file = false;
  std::string_view list(type);
  while (!list.empty()) {
    std::size_t end = std::min(list.find('|'), list.size());
    std::string_view item = list.substr(0, end);
    item = item.substr(0, item.find('['));  // "virtual[:OPTS]": the word before its options
    if (names_file(item) && std::none_of(item.begin(), item.end(), [](char c) { return c >= 'a' && c <= 'z'; }))
      file = true;
    else if (plain_word(item))
      words.emplace_back(item);
    else
      return {};
    list.remove_prefix(std::min(list.size(), end + 1));
  }
  return words.size() >= 2 || (file && !words.empty()) ? words : std::vector<std::string>{};
}

std::string joined(const std::vector<std::string>& words, const char* between) {
  std::string out;
  for (const std::string& w : words) out += (out.empty() ? "" : between) + w;
  return out;
}

std::string function_name(const std::string& program) {
  std::string name = "_" + program;
  for (char& c : name)
    if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9'))) c = '_';
  return name;
}

}  // namespace

std::vector<CompletionEntry> completion_entries(const CLI::App& app) {
  std::vector<CompletionEntry> entries;
  for (const CLI::Option* opt : app.get_options()) {
    if (opt->get_group().empty()) continue;  // hidden from --help, hidden here
    CompletionEntry e;
    std::string type = opt->get_type_name();
    e.takes_value = opt->get_items_expected_max() > 0;  // flags expect none
    e.file_value = e.takes_value && names_file(type);
    if (e.takes_value) e.choices = listed_choices(type);
    if (opt->get_positional()) {
      e.names.push_back("");  // the positional: no name to complete
    } else {
      for (const std::string& s : opt->get_snames()) e.names.push_back("-" + s);
      for (const std::string& l : opt->get_lnames()) e.names.push_back("--" + l);
    }
    entries.push_back(std::move(e));
  }
  return entries;
}

std::string bash_completion(const std::string& program, const std::vector<CompletionEntry>& entries) {
  std::vector<std::string> words, files, numbers;
  std::string choices;
  bool positional = false;
  for (const CompletionEntry& e : entries) {
    if (e.names.size() == 1 && e.names[0].empty()) {
      positional = true;
      continue;
    }
    for (const std::string& n : e.names)
      if (n.rfind("--", 0) == 0) words.push_back(n);
    if (!e.takes_value) continue;
    std::string pattern = joined(e.names, "|");
    if (!e.choices.empty())
      choices += "    " + pattern + ")\n        COMPREPLY=($(compgen -W '" + joined(e.choices, " ") + "' -- \"$cur\")" +
                 (e.file_value ? " $(compgen -f -- \"$cur\")" : "") + "); return 0 ;;\n";
    else if (e.file_value)
      files.push_back(pattern);
    else
      numbers.push_back(pattern);
  }
  std::string fn = function_name(program);
  std::string s = "# bash completion for " + program + ", generated from its own options by `" + program +
                  " --bash-completion`\n";
  s += fn + "()\n{\n";
  s += "  local cur=${COMP_WORDS[COMP_CWORD]} prev=\n";
  s += "  (( COMP_CWORD > 0 )) && prev=${COMP_WORDS[COMP_CWORD-1]}\n";
  s += "  # --option=value: bash splits at '=' (COMP_WORDBREAKS)\n";
  s += "  if [[ $prev == = ]] && (( COMP_CWORD > 1 )); then prev=${COMP_WORDS[COMP_CWORD-2]}; fi\n";
  s += "  if [[ $cur == = ]]; then cur=; fi\n";
  s += "  COMPREPLY=()\n";
  s += "  case $prev in\n" + choices;
  if (!files.empty()) s += "    " + joined(files, "|") + ")\n        COMPREPLY=($(compgen -f -- \"$cur\")); return 0 ;;\n";
  if (!numbers.empty()) s += "    " + joined(numbers, "|") + ")\n        return 0 ;;\n";
  s += "  esac\n";
  s += "  if [[ $cur == -* ]]; then\n";
  s += "    COMPREPLY=($(compgen -W '" + joined(words, " ") + "' -- \"$cur\"))\n";
  s += "    return 0\n  fi\n";
  if (positional) s += "  COMPREPLY=($(compgen -f -- \"$cur\"))\n";
  s += "}\n";
  s += "complete -o filenames -F " + fn + " " + program + "\n";
  return s;
}

}  // namespace gcode::cli
