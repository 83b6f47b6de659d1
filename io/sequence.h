#pragma once
// A sequence: a folder holding frame_0000.exr, frame_0001.exr, ... and manifest.json.
#include <cstdint>
#include <string>
#include <vector>

#include "core/frame.h"
#include "io/exr_frame.h"
#include "io/io_error.h"
#include "io/staged_folder.h"

namespace svgf::io {

struct ManifestFile {
  std::string name;    // file name inside the folder, e.g. "frame_0003.exr"
  std::string sha256;  // lowercase hex of the file's bytes
};

struct Manifest {
  int format_version = 1;
  std::string scene;         // e.g. "cornell-moving", or "synthetic"
  int width = 0;
  int height = 0;
  int spp = 1;               // samples per pixel of `color`
  int reference_spp = 0;     // samples per pixel of `reference`; 0: no reference
  uint64_t seed = 0;
  std::string generator;     // e.g. "svgf-fixtures 1"
  std::vector<ManifestFile> frames;
  std::vector<int> camera_cuts;  // frame numbers where the camera cuts (history must reset)
};

std::string frame_file_name(int index);  // "frame_0003.exr"

// manifest.json of a sequence folder. Throws IoError naming the file on a missing file,
// bad JSON or a missing/ill-typed key.
Manifest read_manifest(const std::string& dir);
void write_manifest(const std::string& dir, const Manifest& manifest);  // atomic

// Opens a sequence for reading frame by frame.
class Sequence {
 public:
  explicit Sequence(const std::string& dir);  // reads and checks the manifest
  const Manifest& manifest() const { return manifest_; }
  const std::string& dir() const { return dir_; }
  int size() const { return static_cast<int>(manifest_.frames.size()); }
  std::string path(int k) const;
  // Reads frame k; throws IoError if its size differs from the manifest's (naming the file).
  // Its index is svgf.frame, or k when the file has none.
  Frame read(int k) const;
  // Frame k's header, checked as read(k) checks it, without reading pixels; the index as read().
  FrameHeader read_header(int k) const;
  bool is_camera_cut(int k) const;
  // Throws IoError naming the file when frame k's SHA-256 differs from the manifest's.
  void verify_checksum(int k) const;

 private:
  std::string dir_;
  Manifest manifest_;
};

// Writes a sequence into `dir` atomically and frame by frame: frames go into a staging sibling
// folder (io::StagedFolder), and commit() writes the manifest (frame names and SHA-256 sums
// filled in) and swaps the folder in, replacing an existing sequence. Destroyed without
// commit(): the staging folder is removed and `dir` is untouched.
class SequenceWriter {
 public:
  SequenceWriter(const std::string& dir, const FrameStorage& storage);
  void add(const Frame& frame);  // written as frame_file_name(number of frames added so far)
  void commit(Manifest manifest);
  // The staging folder, for files that belong with the sequence (svgf import's import.json):
  // they are swapped in with it.
  const std::string& staging_dir() const { return folder_.path(); }

 private:
  StagedFolder folder_;
  FrameStorage storage_;
  std::vector<ManifestFile> files_;
  bool committed_ = false;
  int width_ = 0, height_ = 0;  // of the frames added so far (all must match)
};

}  // namespace svgf::io
