// SPDX-License-Identifier: GPL-2.0-or-later
#include "fuzz/generated_code.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <vector>

#include "fuzz/harness.hpp"
#include "model/names.hpp"

extern char** environ;

namespace kanegen::fuzz {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void failure(const std::string& what) { throw HarnessFailure(what); }

bool word_char(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
}

}  // namespace

std::string shown(const std::string& text) {
  std::string out;
  for (const char c : text) {
    const auto b = static_cast<unsigned char>(c);
    if (b >= 0x20 && b < 0x7f && c != '\\') {
      out += c;
    } else {
      char hex[5];
      std::snprintf(hex, sizeof hex, "\\x%02x", b);
      out += hex;
    }
  }
  return "'" + out + "'";
}

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string preprocess(const fs::path& cpp, const fs::path& runtime_include, const fs::path& out_dir) {
  const std::string include_generated = "-I" + cpp.parent_path().string();
  const std::string include_runtime = "-I" + runtime_include.string();
  const std::string out = (out_dir / "preprocessed.txt").string(), err = (out_dir / "g++.txt").string();
  std::vector<std::string> args{"g++",           "-std=c++17", "-E", "-P", include_generated,
                                include_runtime, cpp.string()};
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = 0;
  const int spawned = posix_spawnp(&pid, "g++", &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) failure("cannot run g++");
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    failure("g++ -E fails on " + cpp.filename().string() + ": " + read_file(err).substr(0, 2000));
  return read_file(out);
}

std::vector<Token> tokenize(const std::string& text) {
  std::vector<Token> tokens;
  std::size_t i = 0;
  while (i < text.size()) {
    const char c = text[i];
    std::size_t end = i + 1;
    if (c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v') {
      ++i;
      continue;
    }
    if (c == '"' || c == '\'') {
      while (end < text.size() && text[end] != c && text[end] != '\n') end += text[end] == '\\' ? 2 : 1;
      end = std::min(end + 1, text.size());
    } else if (c >= '0' && c <= '9') {
      while (end < text.size() && (word_char(text[end]) || text[end] == '.' ||
                                   (text[end] == '\'' && end + 1 < text.size() && word_char(text[end + 1])) ||
                                   ((text[end] == '+' || text[end] == '-') &&
                                    std::string("eEpP").find(text[end - 1]) != std::string::npos)))
        ++end;
    } else if (word_char(c)) {
      while (end < text.size() && word_char(text[end])) ++end;
    }
    tokens.push_back({text.substr(i, end - i), c == '"'});
    i = end;
  }
  return tokens;
}

std::string decode_literal(const std::string& token) {
  if (token.size() < 2 || token.front() != '"' || token.back() != '"')
    failure("unterminated literal " + token);
  std::string out;
  for (std::size_t i = 1; i + 1 < token.size(); ++i) {
    if (token[i] != '\\') {
      out += token[i];
      continue;
    }
    const char e = token[++i];
    static const std::string simple = "abfnrtv\\\"'?", value = "\a\b\f\n\r\t\v\\\"'?";
    if (simple.find(e) != std::string::npos) {
      out += value[simple.find(e)];
    } else if (e >= '0' && e <= '7') {
      int code = 0;
      std::size_t n = 0;
      for (; n < 3 && token[i + n] >= '0' && token[i + n] <= '7'; ++n) code = code * 8 + (token[i + n] - '0');
      out += static_cast<char>(code);
      i += n - 1;
    } else if (e == 'x') {
      int code = 0;
      while (std::isxdigit(static_cast<unsigned char>(token[i + 1]))) {
        const char h = static_cast<char>(std::tolower(static_cast<unsigned char>(token[++i])));
        code = code * 16 + (h <= '9' ? h - '0' : h - 'a' + 10);
      }
      out += static_cast<char>(code);
    } else {
      failure("unknown escape in the literal " + token);
    }
  }
  return out;
}

std::string substitute(const std::string& text, const NameMap& names) {
  std::string out;
  for (std::size_t i = 0; i < text.size();) {
    bool replaced = false;
    for (const auto& [placeholder, name] : names) {
      if (text.compare(i, placeholder.size(), placeholder) == 0) {
        out += name;
        i += placeholder.size();
        replaced = true;
        break;
      }
    }
    if (!replaced) out += text[i++];
  }
  return out;
}

void compare_tokens(const std::string& file, const std::vector<Token>& placeheld,
                    const std::vector<Token>& fuzzed, const NameMap& names, bool literals) {
  const std::size_t n = std::min(placeheld.size(), fuzzed.size());
  for (std::size_t i = 0; i < n; ++i) {
    const Token& p = placeheld[i];
    const Token& f = fuzzed[i];
    const auto where = [&] {
      std::string context;
      for (std::size_t k = i >= 8 ? i - 8 : 0; k < std::min(n, i + 8); ++k) context += fuzzed[k].text + " ";
      return file + ": token " + std::to_string(i) + " is " + shown(f.text) +
             " where the placeholder model has " + shown(p.text) + " (fuzzed context: " + shown(context) +
             ")";
    };
    if (p.literal != f.literal) failure(where());
    if (p.literal && !literals) continue;
    if (p.literal) {
      const std::string expected = substitute(decode_literal(p.text), names);
      if (decode_literal(f.text) != expected)
        failure(where() + ": the literal reads " + shown(decode_literal(f.text)) + ", not " +
                shown(expected));
      continue;
    }
    const std::string expected = substitute(p.text, names);
    if (f.text != expected) failure(where());
    if (expected != p.text && (!model::is_identifier(expected) || model::is_cpp_keyword(expected)))
      failure(where() + ": a name used as an identifier is not a usable one");
  }
  if (placeheld.size() != fuzzed.size())
    failure(file + ": " + std::to_string(fuzzed.size()) + " tokens, the placeholder model's " +
            std::to_string(placeheld.size()));
}

}  // namespace kanegen::fuzz
