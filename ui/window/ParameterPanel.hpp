#pragma once
/// \file ParameterPanel.hpp
/// \brief The settings of a trapping run (Karney 1983, appendix B, step 1), validated as they are typed.
///
/// Every field is a text field (T and M reach 10¹⁰ and beyond, more than a spin box holds).  After each
/// keystroke the panel parses each field, asks core's validationErrors() for every broken rule, marks every
/// field they name (its tooltip gives its own reason), lists the reasons in the order of the form with the
/// ranges of core's parameterRules() and kMaxThreads, and reports validity (the main window enables Run from
/// it).  The preset's description keeps a fixed height, so the fields below it never move.  The integer
/// map coefficients (A, B, C, m) that core derives from K, xmin, xmax are shown read-only: they, not K,
/// define the map exactly.

#include <QList>
#include <QMap>
#include <QWidget>

#include <optional>

#include "core/runspec/RunSpec.hpp"

class QComboBox;
class QFormLayout;
class QLabel;
class QLineEdit;

namespace archipelago::ui {

class ParameterPanel : public QWidget {
  Q_OBJECT
 public:
  explicit ParameterPanel(QWidget* parent = nullptr);

  /// The parameters when every field is valid.
  [[nodiscard]] std::optional<TrappingParameters> parameters() const;
  /// Worker threads (0 = every core).
  [[nodiscard]] int threads() const;
  [[nodiscard]] bool isValid() const noexcept { return valid_; }
  /// Every reason the parameters are invalid, one a line in the order of the form (empty when valid).
  [[nodiscard]] QString validationMessage() const;
  /// The first field in the order of the form that a broken rule is mainly about (subsets, not M, for
  /// subsets > M; empty when valid).
  [[nodiscard]] QString invalidField() const { return invalidField_; }
  /// Every invalid field, in the order of the form.
  [[nodiscard]] QStringList invalidFields() const { return invalidFields_; }
  /// The reasons about one field, one a line (empty when the field is valid).
  [[nodiscard]] QString fieldError(const QString& name) const;

  void setParameters(const TrappingParameters& p, int threads);
  /// The run specification of the fields (parameters, threads, and the preset's name when one is chosen),
  /// when every field is valid: what the window saves and restores through core's codec.
  [[nodiscard]] std::optional<RunSpec> spec() const;
  /// Fills the fields from a spec; the preset box shows the preset whose parameters these are, else Custom.
  void setSpec(const RunSpec& spec);
  [[nodiscard]] QStringList presetNames() const;
  /// Loads the preset of that name or id (core's findPreset); false when there is none.
  bool applyPreset(const QString& nameOrId);
  /// Fields are read-only while a run computes or can be resumed (its parameters cannot change under it): they then
  /// look it, and a note above them says why and how to edit.
  void setEditable(bool editable);
  /// The text field of a parameter ("K", "xmin", "xmax", "Xr", "q", "T", "M", "seed", "subsets", "threads").
  [[nodiscard]] QLineEdit* field(const QString& name) const { return fields_.value(name); }

 Q_SIGNALS:
  void validityChanged(bool valid);
  void parametersChanged();

 private:
  void addField(QFormLayout* form, const QString& name, const QString& label, const QString& tooltip);
  /// The note shown above the fields while they are read-only (setEditable).
  QLabel* createLockedNote();
  void revalidate();
  void markField(const QString& name, const QString& error);
  void showDerived(const std::optional<TrappingParameters>& p);
  void showPreset(const Preset* preset);
  /// The preset whose parameters the fields hold (nullptr: none, or the fields are invalid).
  [[nodiscard]] const Preset* matchingPreset() const;

  QComboBox* presetBox_ = nullptr;
  QLabel* presetDescription_ = nullptr;
  QLabel* message_ = nullptr;
  QLabel* lockedNote_ = nullptr;   ///< shown while the fields are read-only
  QMap<QString, QLineEdit*> fields_;
  QMap<QString, QLabel*> derived_;
  std::optional<TrappingParameters> parsed_;
  QStringList invalidFields_;
  QString invalidField_;
  QString reason_;
  bool valid_ = false;
};

}  // namespace archipelago::ui
