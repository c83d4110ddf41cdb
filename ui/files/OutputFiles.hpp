#pragma once
/// \file OutputFiles.hpp
/// \brief Every image and document the GUI and the report write: rendered in memory, checked, then published
/// atomically (core/io/AtomicFile.hpp), so that a full disk, a killed process or a failing encoder never
/// leaves a truncated PNG, SVG or PDF behind, and never passes silently (issue #23: a report once exited 0
/// with a PDF cut at 3 of its 3.8 MB).

#include <QByteArray>
#include <QString>

#include "core/provenance/Provenance.hpp"

class QImage;

namespace archipelago::ui {

/// Writes `bytes` to `path` atomically.  False, with the reason in *error, when it cannot.
bool publishBytes(const QByteArray& bytes, const QString& path, QString* error);

/// Encodes `image` as PNG in memory, with the fields of `provenance` as its text chunks (where it came from: the
/// program, version and commit at least; issue 42), and publishes it.  False, with the reason, when encoding or
/// writing fails.
bool writePngFile(const QImage& image, const QString& path, QString* error,
                  const Provenance& provenance = programProvenance());

/// Whether `bytes` look like a whole PDF document: "%PDF-" at the start and "%%EOF" in its last 1024 bytes.
[[nodiscard]] bool isCompletePdf(const QByteArray& bytes);

/// Whether `bytes` look like a whole SVG document: "<svg" near the start and "</svg>" near the end.
[[nodiscard]] bool isCompleteSvg(const QByteArray& bytes);

}  // namespace archipelago::ui
