// The importers' line reader: words, strict finite numbers, errors naming file and line.
#include "packing/text_lines.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "core/error.hpp"

namespace granwave::packing {

TextFile::TextFile(const std::string& path) : path_(path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open the packing file");
  std::string text;
  std::size_t n = 0;
  while (std::getline(in, text)) {
    if (!text.empty() && text.back() == '\r') text.pop_back();
    TextLine line{++n, {}, text};
    std::istringstream words(text);
    for (std::string w; words >> w;) line.words.push_back(w);
    lines_.push_back(std::move(line));
  }
  if (in.bad()) throw InputError(path + ": read error");
}

std::string TextFile::at(const TextLine& line) const { return path_ + ":" + std::to_string(line.number); }

double TextFile::number(const TextLine& line, std::size_t word, const char* field) const {
  if (word >= line.words.size())
    throw InputError(at(line) + ": missing " + field + " (column " + std::to_string(word + 1) + ") in \"" +
                     line.text + "\"");
  const std::string& w = line.words[word];
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(w.c_str(), &end);
  if (end == w.c_str() || *end != '\0')
    throw InputError(at(line) + ": " + field + " \"" + w + "\" is not a number");
  if (!std::isfinite(v) || errno == ERANGE)
    throw InputError(at(line) + ": " + field + " \"" + w + "\" is not a finite number (allowed: finite values)");
  return v;
}

std::int64_t TextFile::integer(const TextLine& line, std::size_t word, const char* field) const {
  if (word >= line.words.size())
    throw InputError(at(line) + ": missing " + field + " (column " + std::to_string(word + 1) + ")");
  const std::string& w = line.words[word];
  char* end = nullptr;
  errno = 0;
  const long long v = std::strtoll(w.c_str(), &end, 10);
  if (end == w.c_str() || *end != '\0' || errno == ERANGE)
    throw InputError(at(line) + ": " + field + " \"" + w + "\" is not an integer");
  return v;
}

double positive_radius(const TextFile& file, const TextLine& line, double radius, std::int64_t id) {
  if (!(radius > 0.0))
    throw InputError(file.at(line) + ", particle id " + std::to_string(id) + ": radius " + std::to_string(radius) +
                     " is not positive (allowed: radius > 0)");
  return radius;
}

Packing text_packing(const TextFile& file, const Box& box) {
  Packing packing;
  packing.source = file.path();
  packing.box = box;
  return packing;
}

Particle sphere_of(const TextFile& file, const TextLine& line, std::size_t first, std::int64_t id) {
  Particle p;
  p.line = line.number;
  p.id = id;
  p.centre = Vec3(file.number(line, first, "x"), file.number(line, first + 1, "y"), file.number(line, first + 2, "z"));
  p.radius = positive_radius(file, line, file.number(line, first + 3, "r"), p.id);
  return p;
}

}  // namespace granwave::packing
