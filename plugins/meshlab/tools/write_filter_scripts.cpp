// Writes sample_projects/meshlab/*.mlx: one meshlabserver script per filter
// with every parameter at its default, in declaration order (meshlabserver
// aborts otherwise). Attributes come from MeshLab's own parameter writer
// (RichParameter::fillToXMLDocument), in a fixed order so that the files do
// not change between runs (QDomDocument orders them by a seeded hash).
//   meshnbv_write_filter_scripts OUT_DIR
// The test meshlab/scripts.* checks that the committed files match.
#include <algorithm>
#include <cstdio>

#include <QCoreApplication>
#include <QDir>
#include <QDomDocument>
#include <QFile>
#include <QXmlStreamWriter>

#include <common/filter_parameter/rich_parameter_list.h>

#include "filter_meshnbv.h"

namespace {

// type, name, value, the type's own attributes (enum values in order),
// then description and tooltip.
QStringList ordered_attributes(const QDomElement& e) {
  QStringList first{"type", "name", "value"}, last{"description", "tooltip"}, middle;
  const QDomNamedNodeMap attributes = e.attributes();
  for (int i = 0; i < attributes.count(); ++i) {
    const QString name = attributes.item(i).nodeName();
    if (!first.contains(name) && !last.contains(name)) middle << name;
  }
  std::sort(middle.begin(), middle.end(), [](const QString& a, const QString& b) {
    const bool ea = a.startsWith("enum_val"), eb = b.startsWith("enum_val");
    if (ea && eb) return a.mid(8).toInt() < b.mid(8).toInt();
    return ea != eb ? ea : a < b;
  });
  QStringList out;
  for (const QString& name : first + middle + last)
    if (e.hasAttribute(name)) out << name;
  return out;
}

bool write_script(const QString& path, const QString& filter, const RichParameterList& parameters) {
  QByteArray text;
  QXmlStreamWriter xml(&text);
  xml.setAutoFormatting(true);
  xml.setAutoFormattingIndent(1);
  xml.writeStartElement("FilterScript");
  xml.writeStartElement("filter");
  xml.writeAttribute("name", filter);
  QDomDocument doc;
  for (const RichParameter& p : parameters) {
    const QDomElement e = p.fillToXMLDocument(doc);
    xml.writeStartElement("Param");
    for (const QString& name : ordered_attributes(e)) xml.writeAttribute(name, e.attribute(name));
    xml.writeEndElement();
  }
  xml.writeEndElement();
  xml.writeEndElement();
  xml.writeEndDocument();  // ends with a newline
  if (xml.hasError()) return false;
  QFile file(path);
  if (!file.open(QIODevice::WriteOnly | QIODevice::Truncate)) return false;
  // The writer starts with a newline: the DOCTYPE goes first, as MeshLab writes it.
  file.write("<!DOCTYPE FilterScript>\n" + text.mid(text.indexOf('<')));
  return file.flush();
}

}  // namespace

int main(int argc, char** argv) {
  QCoreApplication app(argc, argv);
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUT_DIR\n", argv[0]);
    return 2;
  }
  const QDir out(QString::fromLocal8Bit(argv[1]));
  FilterMeshNbvPlugin plugin;
  MeshDocument document;
  const struct {
    int id;
    const char* file;
  } scripts[] = {{FilterMeshNbvPlugin::FP_COMPUTE_PRI, "compute_pri.mlx"},
                 {FilterMeshNbvPlugin::FP_SUGGEST_NEXT_VIEW, "suggest_next_view.mlx"},
                 {FilterMeshNbvPlugin::FP_SELECT_WORST_FACES, "select_worst_faces.mlx"}};
  for (const auto& s : scripts) {
    RichParameterList parameters;
    plugin.initParameterSet(plugin.AC(s.id), document, parameters);
    const QString path = out.filePath(s.file);
    if (!write_script(path, plugin.filterName(s.id), parameters)) {
      std::fprintf(stderr, "cannot write %s\n", qUtf8Printable(path));
      return 1;
    }
    std::printf("%s\n", qUtf8Printable(path));
  }
  return 0;
}
