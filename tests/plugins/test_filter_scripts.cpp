// The sample scripts (sample_projects/meshlab/*.mlx) list every parameter
// of their filter, in declaration order, at its default (meshlabserver
// aborts on a script that does not); the help text names every parameter
// and cites the paper.
#include <QDomDocument>
#include <QFile>

#include <gtest/gtest.h>

#include <common/filterscript.h>

#include "filter_meshnbv.h"
#include "meshlab_test_support.h"

namespace {

struct Case {
  int id;
  const char* script;
};
const Case kCases[] = {{FilterMeshNbvPlugin::FP_COMPUTE_PRI, "compute_pri"},
                       {FilterMeshNbvPlugin::FP_SUGGEST_NEXT_VIEW, "suggest_next_view"},
                       {FilterMeshNbvPlugin::FP_SELECT_WORST_FACES, "select_worst_faces"}};

}  // namespace

TEST(FilterScripts, SampleScriptsListEveryParameterAtItsDefault) {
  FilterMeshNbvPlugin plugin;
  MeshDocument document;
  for (const Case& c : kCases) {
    SCOPED_TRACE(c.script);
    RichParameterList declared;
    plugin.initParameterSet(plugin.AC(c.id), document, declared);
    FilterScript script;
    ASSERT_TRUE(script.open(QString::fromStdString(meshnbv::meshlab_test::script(c.script))));
    ASSERT_EQ(script.size(), 1);
    EXPECT_EQ(script.front().filterName(), plugin.filterName(c.id));
    const RichParameterList& listed = script.front().second;
    ASSERT_EQ(listed.size(), declared.size());
    QDomDocument doc;
    auto d = declared.begin();
    auto l = listed.begin();
    for (; d != declared.end(); ++d, ++l) {
      const QDomElement a = d->fillToXMLDocument(doc, false), b = l->fillToXMLDocument(doc, false);
      EXPECT_EQ(a.attribute("name").toStdString(), b.attribute("name").toStdString());
      EXPECT_EQ(a.attribute("type").toStdString(), b.attribute("type").toStdString());
      EXPECT_EQ(a.attribute("value").toStdString(), b.attribute("value").toStdString())
          << "parameter " << a.attribute("name").toStdString()
          << " (regenerate with meshnbv_write_filter_scripts)";
    }
  }
}

TEST(FilterScripts, HelpNamesEveryParameterAndCitesThePaper) {
  FilterMeshNbvPlugin plugin;
  MeshDocument document;
  for (const Case& c : kCases) {
    SCOPED_TRACE(c.script);
    RichParameterList declared;
    plugin.initParameterSet(plugin.AC(c.id), document, declared);
    const QString info = plugin.filterInfo(c.id);
    EXPECT_TRUE(info.contains("Predicting the Next Best View for 3D Mesh Refinement"));
    EXPECT_TRUE(info.contains("Morreale"));
    for (const RichParameter& p : declared) {
      EXPECT_TRUE(info.contains("<b>" + p.name() + "</b>")) << p.name().toStdString();
      EXPECT_FALSE(p.toolTip().isEmpty()) << p.name().toStdString();
    }
  }
}
