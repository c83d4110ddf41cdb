#include "ui/files/OutputFiles.hpp"

#include <QBuffer>
#include <QImage>

#include <stdexcept>
#include <string_view>

#include "core/io/AtomicFile.hpp"

namespace archipelago::ui {

bool publishBytes(const QByteArray& bytes, const QString& path, QString* error) {
  try {
    io::writeFileAtomically(path.toStdString(), std::string_view(bytes.constData(), static_cast<std::size_t>(bytes.size())));
  } catch (const std::exception& e) {
    if (error) *error = QString::fromStdString(e.what());
    return false;
  }
  return true;
}

bool writePngFile(const QImage& image, const QString& path, QString* error, const Provenance& provenance) {
  QByteArray bytes;
  QBuffer buffer(&bytes);
  buffer.open(QIODevice::WriteOnly);
  QImage annotated = image;
  for (const auto& [key, value] : provenance.fields)
    annotated.setText(QString::fromStdString(key), QString::fromStdString(value));  // Qt writes them as tEXt chunks
  if (annotated.isNull() || !annotated.save(&buffer, "PNG") || bytes.isEmpty()) {
    if (error) *error = QStringLiteral("cannot encode %1 as PNG").arg(path);
    return false;
  }
  return publishBytes(bytes, path, error);
}

bool isCompletePdf(const QByteArray& bytes) {
  return bytes.startsWith("%PDF-") && bytes.right(1024).contains("%%EOF");
}

bool isCompleteSvg(const QByteArray& bytes) {
  return bytes.left(4096).contains("<svg") && bytes.right(64).contains("</svg>");
}

}  // namespace archipelago::ui
