#include "ui/window/ParameterPanel.hpp"

#include <QComboBox>
#include <QFormLayout>
#include <QGroupBox>
#include <QLabel>
#include <QPalette>
#include <QLineEdit>
#include <QLocale>
#include <QScrollArea>
#include <QSignalBlocker>
#include <QThread>
#include <QVBoxLayout>

#include <cmath>
#include <limits>
#include <variant>

#include "core/runspec/InputRules.hpp"

namespace archipelago::ui {

namespace {
/// The fields in the order of the form.
const QStringList kFieldOrder = {QStringLiteral("K"),    QStringLiteral("xmin"), QStringLiteral("xmax"),
                                 QStringLiteral("Xr"),   QStringLiteral("q"),    QStringLiteral("T"),
                                 QStringLiteral("M"),    QStringLiteral("seed"), QStringLiteral("subsets"),
                                 QStringLiteral("threads")};

const QLocale kNumbers = QLocale::c();  // the paper's notation: a point and an exponent, never a comma

/// A field's value through core's one input layer (core/runspec/InputRules.hpp, "2e7" an integer as everywhere), or
/// its message; surrounding blanks are not part of a typed number.
std::variant<ParameterValue, QString> input(const QString& key, const QString& text) {
  try {
    return readInput(key.toStdString(), text.trimmed().toStdString());
  } catch (const std::exception& e) {
    return QString::fromStdString(e.what());
  }
}

/// The shortest text that reads back as exactly v (0.1, not 0.10000000000000001).
QString shortest(double v) {
  for (int digits = 1; digits < 17; ++digits) {
    const QString text = kNumbers.toString(v, 'g', digits);
    if (kNumbers.toDouble(text) == v) return text;
  }
  return kNumbers.toString(v, 'g', 17);
}

QString groupedCount(double v) {
  return v < 1e6 ? kNumbers.toString(v, 'f', 0) : kNumbers.toString(v, 'g', 4).replace(QStringLiteral("e+"), QStringLiteral("e"));
}
}  // namespace

ParameterPanel::ParameterPanel(QWidget* parent) : QWidget(parent) {
  auto* layout = new QVBoxLayout(this);

  presetBox_ = new QComboBox(this);
  presetBox_->setObjectName(QStringLiteral("presets"));
  presetBox_->setToolTip(tr("Parameter sets of the paper's figures; choosing one fills the fields below."));
  presetBox_->addItem(tr("Custom"));
  for (const Preset& p : presets()) presetBox_->addItem(QString::fromStdString(p.spec.name));
  presetDescription_ = new QLabel(this);
  presetDescription_->setObjectName(QStringLiteral("presetDescription"));
  presetDescription_->setWordWrap(true);
  presetDescription_->setAlignment(Qt::AlignLeft | Qt::AlignTop);
  presetDescription_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  // Ordinary text (a grey caption read as disabled) in a frameless area of a fixed height of five lines whether a
  // preset is chosen or not, so that the fields below never move; a longer text scrolls (it was cut mid-line), and
  // the whole text is in the tooltip.
  auto* descriptionArea = new QScrollArea(this);
  descriptionArea->setObjectName(QStringLiteral("presetDescriptionArea"));
  descriptionArea->setFrameShape(QFrame::NoFrame);
  descriptionArea->setWidgetResizable(true);
  descriptionArea->setHorizontalScrollBarPolicy(Qt::ScrollBarAlwaysOff);
  descriptionArea->setWidget(presetDescription_);
  descriptionArea->setFixedHeight(presetDescription_->fontMetrics().lineSpacing() * 5 + 4);
  layout->addWidget(createLockedNote());
  auto* presetForm = new QFormLayout;
  presetForm->addRow(tr("Preset"), presetBox_);
  layout->addLayout(presetForm);
  layout->addWidget(descriptionArea);

  auto* mapGroup = new QGroupBox(tr("Map Q*  (y′ = y + 2(x² − K),  x′ = x + y′)"), this);
  auto* mapForm = new QFormLayout(mapGroup);
  addField(mapForm, QStringLiteral("K"), QStringLiteral("K"),
           tr("The map parameter K of Q (§2). Small |K| is nearly integrable (§4); at K = 0.1 the "
              "central island is ringed by a chain of six islands (§5)."));
  addField(mapForm, QStringLiteral("xmin"), QStringLiteral("x<sub>min</sub>"),
           tr("Left edge of the box of Q* (§2). Must be < −√K so that the elliptic fixed point "
              "(−√K, 0) lies inside the box (appendix B)."));
  addField(mapForm, QStringLiteral("xmax"), QStringLiteral("x<sub>max</sub>"),
           tr("Right edge of the box. Q* is periodic with period L = xmax − xmin in x and y; an orbit that "
              "leaves the box has escaped the islands and its trapped segment ends (§3)."));
  layout->addWidget(mapGroup);

  auto* runGroup = new QGroupBox(tr("Trapping run (appendix B)"), this);
  auto* runForm = new QFormLayout(runGroup);
  addField(runForm, QStringLiteral("Xr"), QStringLiteral("X<sub>r</sub>"),
           tr("Width of the randomizing zone 0 ≤ X ≤ Xr on the left edge of the unit square (appendix B, "
              "step 6): there Y gets a random kick, so successive segments are independent."));
  addField(runForm, QStringLiteral("q"), QStringLiteral("q"),
           tr("Steps of N⁻¹ per block: statistics are gathered for the q-th power of N⁻¹, so segment lengths t are multiples "
              "of q (appendix B). Larger q is cheaper per step but blurs t < q."));
  addField(runForm, QStringLiteral("T"), QStringLiteral("T"),
           tr("Blocks per orbit: each orbit is qT steps long. The paper's K = 0.1 run has qT = 2×10⁹ (§5). "
              "Scientific notation (2e7) is accepted."));
  addField(runForm, QStringLiteral("M"), QStringLiteral("M"),
           tr("Number of independent orbits; the paper's K = 0.1 run used M = 1600 (appendix B)."));
  addField(runForm, QStringLiteral("seed"), tr("seed"),
           tr("Seed of the counter-based random kicks: the same seed gives bit-identical results on any "
              "number of threads, and after pause/resume."));
  addField(runForm, QStringLiteral("subsets"), tr("subsets"),
           tr("Orbits are split into this many independent subsets (orbit i → subset i mod subsets); the "
              "spread between them gives the error bands, the paper's method for D = 6400 ± 800 (§5)."));
  addField(runForm, QStringLiteral("threads"), tr("threads"),
           tr("Worker threads for the run (0 = every core, at most %1). Results do not depend on it.").arg(kMaxThreads));
  layout->addWidget(runGroup);

  message_ = new QLabel(this);
  message_->setObjectName(QStringLiteral("validationMessage"));
  message_->setWordWrap(true);
  message_->setStyleSheet(QStringLiteral("color: #b00020;"));
  layout->addWidget(message_);

  auto* derivedGroup = new QGroupBox(tr("Derived (read-only)"), this);
  derivedGroup->setToolTip(tr("The integers that define the fixed-point map N exactly (appendix B, step 3): "
                              "G(X) = 2ᵐ(A X² − B X + C) in units of 2⁻⁵²."));
  auto* derivedForm = new QFormLayout(derivedGroup);
  const QList<QPair<QString, QString>> derivedRows = {
      {QStringLiteral("A"), QStringLiteral("A = 2L·2<sup>52−m</sup>")},
      {QStringLiteral("B"), QStringLiteral("B = −4x<sub>min</sub>·2<sup>52−m</sup>")},
      {QStringLiteral("C"), QStringLiteral("C = c·2<sup>52−m</sup>")},
      {QStringLiteral("m"), QStringLiteral("m")},
      {QStringLiteral("L"), QStringLiteral("L")},
      {QStringLiteral("steps"), tr("steps M·q·T")}};
  for (const auto& [key, label] : derivedRows) {
    auto* value = new QLabel(QStringLiteral("—"), derivedGroup);
    value->setTextInteractionFlags(Qt::TextSelectableByMouse);
    value->setObjectName(QStringLiteral("derived_") + key);
    derivedForm->addRow(label, value);
    derived_.insert(key, value);
  }
  layout->addWidget(derivedGroup);
  layout->addStretch(1);

  connect(presetBox_, qOverload<int>(&QComboBox::activated), this, [this](int index) {
    if (index > 0) applyPreset(QString::fromStdString(presets()[static_cast<std::size_t>(index - 1)].id));
  });

  if (!presets().empty()) applyPreset(QString::fromStdString(presets().front().id));
  else setParameters(TrappingParameters{}, 0);
}

void ParameterPanel::addField(QFormLayout* form, const QString& name, const QString& label, const QString& tooltip) {
  auto* edit = new QLineEdit(this);
  edit->setObjectName(name);
  edit->setProperty("help", tooltip);
  edit->setToolTip(tooltip);
  edit->setClearButtonEnabled(false);
  auto* caption = new QLabel(label, this);
  caption->setToolTip(tooltip);
  caption->setBuddy(edit);
  form->addRow(caption, edit);
  fields_.insert(name, edit);
  connect(edit, &QLineEdit::textEdited, this, [this] {
    // Edited by hand: the preset these parameters are, or Custom (issue 37, finding 3: typing a preset's value
    // back left "Custom" although every field held the preset).
    revalidate();
    showPreset(matchingPreset());
  });
}

std::optional<TrappingParameters> ParameterPanel::parameters() const { return valid_ ? parsed_ : std::nullopt; }

int ParameterPanel::threads() const {
  const auto n = input(QStringLiteral("threads"), fields_.value(QStringLiteral("threads"))->text());
  const auto* v = std::get_if<ParameterValue>(&n);
  return v ? static_cast<int>(std::get<std::uint64_t>(*v)) : 0;
}

QString ParameterPanel::validationMessage() const { return reason_; }

QString ParameterPanel::fieldError(const QString& name) const {
  const QLineEdit* edit = fields_.value(name);
  return edit ? edit->property("error").toString() : QString();
}

void ParameterPanel::setParameters(const TrappingParameters& p, int threads) {
  fields_[QStringLiteral("K")]->setText(shortest(p.map.K));
  fields_[QStringLiteral("xmin")]->setText(shortest(p.map.xmin));
  fields_[QStringLiteral("xmax")]->setText(shortest(p.map.xmax));
  fields_[QStringLiteral("Xr")]->setText(shortest(p.Xr));
  fields_[QStringLiteral("q")]->setText(QString::number(p.q));
  fields_[QStringLiteral("T")]->setText(QString::number(p.T));
  fields_[QStringLiteral("M")]->setText(QString::number(p.M));
  fields_[QStringLiteral("seed")]->setText(QString::number(p.seed));
  fields_[QStringLiteral("subsets")]->setText(QString::number(p.subsets));
  fields_[QStringLiteral("threads")]->setText(QString::number(threads));
  revalidate();
  showPreset(matchingPreset());
}

const Preset* ParameterPanel::matchingPreset() const {
  // The preset box names the preset these parameters are, or Custom: never a preset the fields have left.
  if (!parsed_) return nullptr;
  const Preset* match = nullptr;
  for (const Preset& preset : presets())
    if (preset.spec.parameters == *parsed_) match = &preset;
  return match;
}

std::optional<RunSpec> ParameterPanel::spec() const {
  const auto p = parameters();
  if (!p) return std::nullopt;
  RunSpec s;
  s.parameters = *p;
  s.threads = threads();
  if (const int i = presetBox_->currentIndex(); i > 0) {
    const Preset& preset = presets()[static_cast<std::size_t>(i - 1)];
    s.name = preset.spec.name;
    s.description = preset.spec.description;
    s.companion = s.parameters.q > 1 ? preset.spec.companion : 0;
  }
  return s;
}

void ParameterPanel::setSpec(const RunSpec& spec) { setParameters(spec.parameters, spec.threads); }

void ParameterPanel::showPreset(const Preset* preset) {
  const QSignalBlocker block(presetBox_);
  const auto all = presets();
  presetBox_->setCurrentIndex(preset ? static_cast<int>(preset - all.data()) + 1 : 0);
  const QString description = preset ? QString::fromStdString(preset->spec.description) : QString();
  presetDescription_->setText(preset ? description : tr("Custom parameters."));
  presetDescription_->setToolTip(description);
}

QStringList ParameterPanel::presetNames() const {
  QStringList names;
  for (const Preset& p : presets()) names << QString::fromStdString(p.spec.name);
  return names;
}

bool ParameterPanel::applyPreset(const QString& nameOrId) {
  const Preset* preset = findPreset(nameOrId.toStdString());
  if (!preset) return false;
  setParameters(preset->spec.parameters, threads());
  showPreset(preset);
  return true;
}

QLabel* ParameterPanel::createLockedNote() {
  lockedNote_ = new QLabel(tr("Read-only: the parameters of the run on screen, which computes or can be resumed. "
                               "Stop it (Shift+F5), or open or start another run, to change them."),
                            this);
  lockedNote_->setObjectName(QStringLiteral("parametersLocked"));
  lockedNote_->setWordWrap(true);
  lockedNote_->setStyleSheet(QStringLiteral("#parametersLocked { background: #eef3fb; border: 1px solid #b8c8e0; "
                                            "padding: 3px; }"));
  lockedNote_->hide();
  return lockedNote_;
}

void ParameterPanel::setEditable(bool editable) {
  // Read-only fields look it (the window's background, not the editable white) and the note above them says why
  // (issue 53, finding 21: a paused run's fields looked editable and dropped the keys without a word).
  for (QLineEdit* edit : std::as_const(fields_)) {
    edit->setReadOnly(!editable);
    QPalette look = edit->palette();
    look.setColor(QPalette::Base, palette().color(editable ? QPalette::Base : QPalette::Window));
    edit->setPalette(look);
  }
  presetBox_->setEnabled(editable);
  lockedNote_->setVisible(!editable);
}

void ParameterPanel::markField(const QString& name, const QString& error) {
  QLineEdit* edit = fields_.value(name);
  if (!edit) return;
  const bool invalid = !error.isEmpty();
  edit->setProperty("invalid", invalid);
  edit->setProperty("error", error);
  // The field's own reason first, then what the field means.
  const QString help = edit->property("help").toString();
  edit->setToolTip(invalid ? QStringLiteral("<p><b>%1</b></p><p>%2</p>").arg(error.toHtmlEscaped().replace(QLatin1Char('\n'), QStringLiteral("<br>")), help)
                           : help);
  edit->setStyleSheet(invalid ? QStringLiteral("QLineEdit { background: #fde7e9; border: 1px solid #b00020; }")
                              : QString());
}

void ParameterPanel::revalidate() {
  // Each field is parsed on its own; a field that does not parse is reported with the range of its rule and
  // left out of the cross-field rules (core's validationErrors() on the other fields), so that every wrong
  // field is marked at once, each with its own reason.
  QMap<QString, QStringList> errors;  // field → its messages
  QStringList messages;               // in the order they were found
  QStringList badFields;
  QStringList primaryFields;  // the first field of each rule: the one it is mainly about
  const auto addError = [&](const QStringList& fields, const QString& message) {
    if (!fields.isEmpty()) primaryFields << fields.front();
    for (const QString& f : fields)
      if (!errors.contains(f)) badFields << f;
    for (const QString& f : fields) errors[f] << message;
    messages << message;
  };
  QStringList unparsed;
  TrappingParameters p;  // fields that do not parse keep their default value, and their rules are skipped
  // Every field through core's one input layer: its value, or its rule's one message.
  const auto read = [&](const char* key) -> std::optional<ParameterValue> {
    const auto v = input(QLatin1String(key), fields_.value(QLatin1String(key))->text());
    if (const auto* value = std::get_if<ParameterValue>(&v)) return *value;
    unparsed << QLatin1String(key);
    addError({QLatin1String(key)}, std::get<QString>(v));
    return std::nullopt;
  };
  for (const char* key : {"K", "xmin", "xmax", "Xr", "q", "T", "M", "seed", "subsets"})
    if (const auto v = read(key)) {
      try {
        setParameterValue(p, key, *v);
      } catch (const std::exception& e) {  // a value its member cannot hold (q > 2³²): the rule's range
        unparsed << QLatin1String(key);
        addError({QLatin1String(key)}, QString::fromStdString(e.what()));
      }
    }
  (void)read("threads");
  for (const ParameterError& e : validationErrors(p)) {
    QStringList fields;
    bool aboutUnparsed = false;
    for (const std::string& f : e.fields) {
      fields << QString::fromStdString(f);
      aboutUnparsed = aboutUnparsed || unparsed.contains(fields.back());
    }
    if (!aboutUnparsed) addError(fields, QString::fromStdString(e.message));
  }
  // Messages in the order of the form, so the list reads like the fields.
  QStringList ordered;
  for (const QString& name : kFieldOrder)
    for (const QString& m : errors.value(name))
      if (!ordered.contains(m)) ordered << m;
  for (const QString& m : std::as_const(messages))
    if (!ordered.contains(m)) ordered << m;

  const bool valid = messages.isEmpty();
  parsed_ = valid ? std::optional<TrappingParameters>(p) : std::nullopt;
  invalidFields_.clear();
  invalidField_.clear();
  for (const QString& name : kFieldOrder) {
    if (badFields.contains(name)) invalidFields_ << name;
    if (invalidField_.isEmpty() && primaryFields.contains(name)) invalidField_ = name;
  }
  reason_ = ordered.join(QLatin1Char('\n'));
  for (auto it = fields_.cbegin(); it != fields_.cend(); ++it)
    markField(it.key(), errors.value(it.key()).join(QLatin1Char('\n')));
  message_->setText(reason_);
  showDerived(parsed_);
  const bool changed = valid != valid_;
  valid_ = valid;
  if (changed) Q_EMIT validityChanged(valid_);
  Q_EMIT parametersChanged();
}

void ParameterPanel::showDerived(const std::optional<TrappingParameters>& p) {
  if (!p) {
    for (QLabel* l : std::as_const(derived_)) l->setText(QStringLiteral("—"));
    return;
  }
  const MapCoefficients k = computeCoefficients(p->map);
  derived_[QStringLiteral("A")]->setText(QString::number(k.A));
  derived_[QStringLiteral("B")]->setText(QString::number(k.B));
  derived_[QStringLiteral("C")]->setText(QString::number(k.C));
  derived_[QStringLiteral("m")]->setText(QString::number(k.m));
  derived_[QStringLiteral("L")]->setText(shortest(p->map.width()));
  derived_[QStringLiteral("steps")]->setText(
      groupedCount(static_cast<double>(p->M) * static_cast<double>(p->q) * static_cast<double>(p->T)));
}

}  // namespace archipelago::ui
