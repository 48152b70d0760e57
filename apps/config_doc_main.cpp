// gyro_config_doc DOCS_DIR [--check]: writes the configuration tables generated from the field
// tables into DOCS_DIR's pages (apps/config_doc.hpp); with --check, writes nothing and exits
// 1 if a page differs from what it would write.
#include <fstream>
#include <iostream>
#include <map>
#include <string>

#include "config_doc.hpp"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << "usage: gyro_config_doc DOCS_DIR [--check]\n";
    return 2;
  }
  const std::string dir = argv[1];
  const bool check = argc > 2 && std::string(argv[2]) == "--check";
  std::map<std::string, std::string> pages;
  for (const gyro::doc::Generated& g : gyro::doc::generated_tables()) {
    auto it = pages.find(g.file);
    if (it == pages.end()) it = pages.emplace(g.file, gyro::doc::read_file(dir + "/" + g.file)).first;
    if (!gyro::doc::replace_between(it->second, g.name, g.text)) {
      std::cerr << dir << "/" << g.file << ": no markers for " << g.name << "\n";
      return 2;
    }
  }
  int differ = 0;
  for (const auto& [file, text] : pages) {
    const std::string path = dir + "/" + file;
    if (gyro::doc::read_file(path) == text) continue;
    if (check) {
      std::cerr << path << " differs from the field tables: run gyro_config_doc " << dir << "\n";
      differ = 1;
    } else {
      std::ofstream(path, std::ios::binary) << text;
      std::cerr << "wrote " << path << "\n";
    }
  }
  return differ;
}
