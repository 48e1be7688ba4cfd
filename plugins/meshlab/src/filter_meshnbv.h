// MeshLab 2020.09 filter plugin of MeshNBV: Compute PRI, Suggest Next View,
// Select Worst Faces. A thin adapter: it converts MeshLab's document to the
// core's types (document_scene.h), calls the core and writes the results
// back; every algorithm lives in meshnbv::core.
#pragma once

#include <string>

#include <common/interfaces.h>

class FilterMeshNbvPlugin : public QObject, public MeshFilterInterface {
  Q_OBJECT
  MESHLAB_PLUGIN_IID_EXPORTER(MESH_FILTER_INTERFACE_IID)
  Q_INTERFACES(MeshFilterInterface)

 public:
  enum { FP_COMPUTE_PRI, FP_SUGGEST_NEXT_VIEW, FP_SELECT_WORST_FACES };

  FilterMeshNbvPlugin();
  using MeshFilterInterface::initParameterSet;  // the MeshModel overload stays visible

  QString pluginName() const override;
  QString filterName(FilterIDType filter) const override;
  QString filterInfo(FilterIDType filter) const override;
  FilterClass getClass(QAction* action) override;
  FILTER_ARITY filterArity(QAction* action) const override;
  int getRequirements(QAction* action) override;
  int getPreConditions(QAction* action) const override;
  int postCondition(QAction* action) const override;
  void initParameterSet(QAction* action, MeshDocument& document, RichParameterList& parameters) override;
  bool applyFilter(QAction* action, MeshDocument& document, const RichParameterList& parameters,
                   vcg::CallBackPos* callback) override;

 private:
  void computePri(MeshDocument& document, const RichParameterList& parameters, vcg::CallBackPos* callback);
  void suggestNextView(MeshDocument& document, const RichParameterList& parameters,
                       vcg::CallBackPos* callback);
  void selectWorstFaces(MeshDocument& document, const RichParameterList& parameters);
  void logLine(const std::string& line);
};
