#include <sylva/shader/Preprocessor.hpp>

#include <sylva/core/Error.hpp>

#include <algorithm>
#include <set>
#include <sstream>

namespace sylva::shader {

namespace {

std::string trimLeft(const std::string& line) {
  const auto first = line.find_first_not_of(" \t");
  return first == std::string::npos ? std::string() : line.substr(first);
}

std::string parentOf(const std::string& path) {
  const auto slash = path.rfind('/');
  return slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
}

/** Normalises "a/b/../c" to "a/c"; include paths never leave the library root. */
std::string normalise(const std::string& path) {
  std::vector<std::string> parts;
  std::stringstream in(path);
  std::string part;
  while (std::getline(in, part, '/')) {
    if (part.empty() || part == ".") {
      continue;
    }
    if (part == "..") {
      if (!parts.empty()) {
        parts.pop_back();
      }
      continue;
    }
    parts.push_back(part);
  }
  std::string out;
  for (const auto& p : parts) {
    out += (out.empty() ? "" : "/") + p;
  }
  return out;
}

class Expander {
public:
  Expander(const Library& library, const Defines& defines) : mLibrary(library), mDefines(defines) {}

  Preprocessed run(const std::string& path) {
    const auto text = mLibrary.read(path);
    if (!text) {
      fail("shader '{}': file not found", path);
    }
    expand(path, *text, true);
    return {mOut.str(), mFiles};
  }

private:
  int fileIndex(const std::string& path) {
    const auto it = std::find(mFiles.begin(), mFiles.end(), path);
    if (it != mFiles.end()) {
      return static_cast<int>(it - mFiles.begin());
    }
    mFiles.push_back(path);
    return static_cast<int>(mFiles.size()) - 1;
  }

  void expand(const std::string& path, const std::string& text, bool top) {
    if (std::find(mStack.begin(), mStack.end(), path) != mStack.end()) {
      std::string chain;
      for (const auto& s : mStack) {
        chain += s + " -> ";
      }
      fail("shader '{}': include cycle: {}{}", mStack.front(), chain, path);
    }
    mStack.push_back(path);
    const int index = fileIndex(path);
    std::istringstream in(text);
    std::string line;
    int number = 0;
    bool sawVersion = !top;
    if (!top) {
      mOut << "#line 1 " << index << "\n";
    }
    while (std::getline(in, line)) {
      ++number;
      if (!line.empty() && line.back() == '\r') {
        line.pop_back();
      }
      const std::string trimmed = trimLeft(line);
      if (trimmed.rfind("#version", 0) == 0) {
        if (!top) {
          fail("{}:{}: #version is only allowed in the main file", path, number);
        }
        if (sawVersion) {
          fail("{}:{}: duplicate #version", path, number);
        }
        sawVersion = true;
        mOut << line << "\n";
        for (const auto& [name, value] : mDefines) {
          mOut << "#define " << name << " " << value << "\n";
        }
        mOut << "#line " << number + 1 << " " << index << "\n";
        continue;
      }
      if (!sawVersion && !trimmed.empty() && trimmed.rfind("//", 0) != 0) {
        fail("{}:{}: the first directive must be #version", path, number);
      }
      if (trimmed.rfind("#pragma once", 0) == 0) {
        mOnce.insert(path);
        mOut << "\n";
        continue;
      }
      // `#include <...>` only appears in shared C++/GLSL headers inside `#ifdef __cplusplus`, which GLSL
      // skips.
      if (trimmed.rfind("#include", 0) == 0 && trimmed.find('<') == std::string::npos) {
        const auto open = trimmed.find('"');
        const auto close = trimmed.find('"', open + 1);
        if (open == std::string::npos || close == std::string::npos) {
          fail("{}:{}: malformed #include (expected #include \"path\")", path, number);
        }
        const std::string name = trimmed.substr(open + 1, close - open - 1);
        std::string resolved = normalise(parentOf(path) + name);
        auto included = mLibrary.read(resolved);
        if (!included) {
          resolved = normalise(name);
          included = mLibrary.read(resolved);
        }
        if (!included) {
          fail("{}:{}: cannot find include \"{}\"", path, number, name);
        }
        if (mOnce.count(resolved) == 0) {
          expand(resolved, *included, false);
          mOut << "#line " << number + 1 << " " << index << "\n";
        } else {
          mOut << "\n";
        }
        continue;
      }
      mOut << line << "\n";
    }
    if (top && !sawVersion) {
      fail("{}: missing #version", path);
    }
    mStack.pop_back();
  }

  const Library& mLibrary;
  const Defines& mDefines;
  std::ostringstream mOut;
  std::vector<std::string> mFiles;
  std::vector<std::string> mStack;
  std::set<std::string> mOnce;
};

} // namespace

Preprocessed preprocess(const Library& library, const std::string& path, const Defines& defines) {
  return Expander(library, defines).run(path);
}

} // namespace sylva::shader
