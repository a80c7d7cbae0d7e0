// Reading a text file line by line for the importers: whitespace-split words and strict numbers,
// with every error naming the file and line.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "packing/packing.hpp"

namespace granwave::packing {

struct TextLine {
  std::size_t number = 0;          // 1-based
  std::vector<std::string> words;  // split at whitespace; an empty line has none
  std::string text;
};

class TextFile {
 public:
  explicit TextFile(const std::string& path);  // InputError if it cannot be read
  const std::string& path() const { return path_; }
  const std::vector<TextLine>& lines() const { return lines_; }
  // "path:line"
  std::string at(const TextLine& line) const;
  // The word as a finite number; an InputError names the file, line and what the field is.
  double number(const TextLine& line, std::size_t word, const char* field) const;
  std::int64_t integer(const TextLine& line, std::size_t word, const char* field) const;

 private:
  std::string path_;
  std::vector<TextLine> lines_;
};

// A radius read from a file: finite and > 0, else InputError naming the place and the particle.
double positive_radius(const TextFile& file, const TextLine& line, double radius, std::int64_t id);
// What an importer of a text file fills: no particles yet, the file as source, the caller's box.
Packing text_packing(const TextFile& file, const Box& box);
// A row's sphere: words first..first+3 as x y z r (metres; finite, r > 0), with its line and id.
Particle sphere_of(const TextFile& file, const TextLine& line, std::size_t first, std::int64_t id);

}  // namespace granwave::packing
