// The command-line conventions the caustics programs share (caustics-render,
// caustics-bench, caustics-ceilings): options declared with their handler on top
// of vtksys::CommandLineArguments, the number parsers with their one-line errors,
// VTK's messages kept to one line, and RunMain(), which turns the error kinds into
// one line on stderr and the exit codes (2 for bad arguments, 3 when no OpenGL
// window can be made, 1 for anything else).
#ifndef CausticsCommandLine_h
#define CausticsCommandLine_h

#include "vtkCausticsTimings.h"
#include "vtkCommand.h"
#include "vtkLogger.h"
#include "vtkNew.h"
#include "vtkObject.h"
#include "vtkOutputWindow.h"
#include "vtksys/CommandLineArguments.hxx"

#include <unistd.h> // For isatty

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <iomanip>
#include <iostream>
#include <list>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace caustics_cli
{
/** A user mistake: reported as one line, exit code 2. */
struct UsageError : std::runtime_error
{
  using std::runtime_error::runtime_error;
};

/** No OpenGL window can be made here (no display, no EGL): exit code 3. */
struct NoWindowError : std::runtime_error
{
  using std::runtime_error::runtime_error;
};

/** A finite number, or "OPTION expects a finite number, got 'TEXT'". */
inline double ParseNumber(const std::string& option, const std::string& text)
{
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(value))
  {
    throw UsageError(option + " expects a finite number, got '" + text + "'");
  }
  return value;
}

/** An integer in [low, high]; accepts 1e6-style notation (photon counts). */
inline double ParseCount(
  const std::string& option, const std::string& text, double low, double high)
{
  const double value = ParseNumber(option, text);
  if (value != std::floor(value) || value < low || value > high)
  {
    std::ostringstream message;
    message << option << " expects an integer in [" << low << ", " << high << "], got '" << text
            << "'";
    throw UsageError(message.str());
  }
  return value;
}

/** An int in [low, high] (bounds printed in full, not in 1e6-style notation). */
inline int ParseInteger(const std::string& option, const std::string& text, int low, int high)
{
  const double value = ParseNumber(option, text);
  if (value != std::floor(value) || value < low || value > high)
  {
    throw UsageError(option + " expects an integer in [" + std::to_string(low) + ", " +
      std::to_string(high) + "], got '" + text + "'");
  }
  return static_cast<int>(value);
}

/** The index of `text` among `choices` ("a, b or c" named in the error otherwise). */
inline int ParseChoice(
  const std::string& option, const std::string& text, const std::vector<std::string>& choices)
{
  for (std::size_t i = 0; i < choices.size(); ++i)
  {
    if (choices[i] == text)
    {
      return static_cast<int>(i);
    }
  }
  std::string expected;
  for (std::size_t i = 0; i < choices.size(); ++i)
  {
    expected += (i == 0 ? "" : (i + 1 == choices.size() ? " or " : ", ")) + choices[i];
  }
  throw UsageError(option + " expects " + expected + ", got '" + text + "'");
}

/**
 * The options of one program on vtksys::CommandLineArguments: each is declared
 * once with its handler, which parses and validates its value and throws
 * UsageError naming the problem. Parse() handles the arguments in order and
 * returns those that are no option (the positionals); an unknown "-..." argument
 * and an option without its value are errors too. The help text stays the
 * program's own (grouped and worded for readers), so vtksys's generated help is
 * not used.
 */
class Arguments
{
public:
  using ValueHandler = std::function<void(const std::string& option, const std::string& value)>;

  /** An option that takes the next argument as its value: --name VALUE. */
  void Value(const char* name, ValueHandler handler)
  {
    this->Add(name, vtksys::CommandLineArguments::SPACE_ARGUMENT, std::move(handler));
  }

  /** A flag: --name. */
  void Flag(const char* name, std::function<void()> handler)
  {
    this->Add(name, vtksys::CommandLineArguments::NO_ARGUMENT,
      [handler](const std::string&, const std::string&) { handler(); });
  }

  /**
   * An option whose value may be left out: --name VALUE with VALUE one of `choices`,
   * or --name alone, which means `bare` (e.g. --denoise [on|off]).
   */
  void OptionalChoice(
    const char* name, std::vector<std::string> choices, const char* bare, ValueHandler handler)
  {
    this->OptionalChoices.push_back({ name, std::move(choices), bare, std::move(handler) });
  }

  /** Parses argv[1..]; throws UsageError on the first bad argument. */
  std::vector<std::string> Parse(int argc, char* argv[])
  {
    // The options with an optional value first (vtksys has no such kind).
    std::vector<const char*> rest;
    for (int i = 0; i < argc; ++i)
    {
      const OptionalOption* option = nullptr;
      for (const OptionalOption& o : this->OptionalChoices)
      {
        option = i > 0 && o.Name == argv[i] ? &o : option;
      }
      if (!option)
      {
        rest.push_back(argv[i]);
        continue;
      }
      const bool given = i + 1 < argc &&
        std::find(option->Choices.begin(), option->Choices.end(), argv[i + 1]) !=
          option->Choices.end();
      option->Handler(option->Name, given ? argv[++i] : option->Bare);
    }
    this->Parser.Initialize(static_cast<int>(rest.size()), rest.data());
    this->Parser.StoreUnusedArguments(true);
    if (!this->Parser.Parse())
    {
      if (!this->Error.empty())
      {
        throw UsageError(this->Error);
      }
      // vtksys fails silently only for an option at the end without its value.
      const unsigned int failed = this->Parser.GetLastArgument() + 1;
      throw UsageError(
        std::string(failed < rest.size() ? rest[failed] : "an option") + " needs a value");
    }
    int count = 0;
    char** unused = nullptr;
    this->Parser.GetUnusedArguments(&count, &unused);
    std::vector<std::string> positionals(unused + 1, unused + count); // unused[0] is argv[0]
    this->Parser.DeleteRemainingArguments(count, &unused);
    for (const auto& argument : positionals)
    {
      if (!argument.empty() && argument[0] == '-')
      {
        throw UsageError("unknown option '" + argument + "' (see --help)");
      }
    }
    return positionals;
  }

private:
  struct OptionalOption
  {
    std::string Name;
    std::vector<std::string> Choices;
    std::string Bare;
    ValueHandler Handler;
  };
  std::vector<OptionalOption> OptionalChoices;

  struct Option
  {
    Arguments* Owner;
    ValueHandler Handler;
  };

  void Add(
    const char* name, vtksys::CommandLineArguments::ArgumentTypeEnum type, ValueHandler handler)
  {
    this->Options.push_back({ this, std::move(handler) });
    // The help string must not be null (vtksys formats its own help as options come).
    this->Parser.AddCallback(name, type, &Arguments::Call, &this->Options.back(), "");
  }

  /** vtksys's callback: runs the handler; a UsageError stops parsing with its message. */
  static int Call(const char* argument, const char* value, void* data)
  {
    auto* option = static_cast<Option*>(data);
    try
    {
      option->Handler(argument, value ? value : "");
      return 1;
    }
    catch (const UsageError& e)
    {
      option->Owner->Error = e.what();
      return 0;
    }
  }

  vtksys::CommandLineArguments Parser;
  std::list<Option> Options; // a list: each option's address is its callback's data
  std::string Error;
};
/**
 * VTK's messages, kept to one line each: errors are remembered (what failed names
 * the first one), warnings are printed as "PROGRAM: warning: ...".
 */
class OneLineOutputWindow : public vtkOutputWindow
{
public:
  static OneLineOutputWindow* New() { return new OneLineOutputWindow; }
  void DisplayErrorText(const char* text) override
  {
    if (this->FirstError.empty())
    {
      this->FirstError = LastLine(text);
    }
  }
  void DisplayWarningText(const char* text) override
  {
    std::cerr << this->Program << ": warning: " << LastLine(text) << "\n";
  }
  void DisplayGenericWarningText(const char* text) override { this->DisplayWarningText(text); }
  void DisplayText(const char* text) override { std::cerr << text; }
  /** The first error since the last call, cleared. */
  std::string TakeError()
  {
    std::string error;
    error.swap(this->FirstError);
    return error;
  }
  std::string Program = "caustics";

private:
  /** VTK formats "ERROR: In file, line N\nvtkClass (0x...): message\n\n": keep the message. */
  static std::string LastLine(const char* text)
  {
    std::string message = text ? text : "";
    while (!message.empty() && (message.back() == '\n' || message.back() == ' '))
    {
      message.pop_back();
    }
    const auto newline = message.rfind('\n');
    message = newline == std::string::npos ? message : message.substr(newline + 1);
    const auto colon = message.find("): ");
    return colon == std::string::npos ? message : message.substr(colon + 3);
  }
  std::string FirstError;
};

/** "12 s", "3 min 05 s": a duration for people. */
inline std::string FormatSeconds(double seconds)
{
  std::ostringstream text;
  if (seconds < 90.0)
  {
    text << std::fixed << std::setprecision(seconds < 10.0 ? 1 : 0) << seconds << " s";
  }
  else
  {
    const long total = std::lround(seconds);
    text << total / 60 << " min " << std::setw(2) << std::setfill('0') << total % 60 << " s";
  }
  return text.str();
}

/**
 * Shows the progress of a long computation while it lives, from the
 * vtkCommand::ProgressEvent its source fires (call data: a double in [0, 1]):
 * - on a terminal, one line rewritten in place, "LABEL: 42 %, about 12 s left",
 *   erased when the work is done (what the program prints next takes its place);
 * - otherwise (a log, a pipe, ctest), one line per 10 %:
 *   "LABEL: 40 % after 8.1 s, about 12 s left", and "LABEL: 100 % after 20 s".
 * Nothing is shown when no event comes (a reference loaded from its cache).
 */
class ProgressReport
{
public:
  ProgressReport(vtkObject* source, std::string label, std::ostream& out = std::cout)
    : Source(source)
    , Label(std::move(label))
    , Out(out)
    , Terminal(&out == &std::cout ? isatty(STDOUT_FILENO) != 0 : isatty(STDERR_FILENO) != 0)
  {
    this->Tag = source->AddObserver(vtkCommand::ProgressEvent, this, &ProgressReport::OnProgress);
  }
  ~ProgressReport()
  {
    this->Source->RemoveObserver(this->Tag);
    this->Erase();
  }
  ProgressReport(const ProgressReport&) = delete;
  ProgressReport& operator=(const ProgressReport&) = delete;

  /** Whether the output is a terminal (the line is rewritten) or not (one line per 10 %). */
  void SetTerminal(bool terminal) { this->Terminal = terminal; }

private:
  using Clock = std::chrono::steady_clock;

  void OnProgress(vtkObject*, unsigned long, void* data)
  {
    const double fraction = std::min(1.0, std::max(0.0, *static_cast<double*>(data)));
    const auto now = Clock::now();
    if (!this->Started)
    {
      this->Started = true;
      this->Start = now;
    }
    const double elapsed = std::chrono::duration<double>(now - this->Start).count();
    const int percent = static_cast<int>(std::floor(100.0 * fraction + 1e-9));
    // The rate is known once a little work is done; before that no estimate is given.
    const std::string left = fraction >= 0.01 && fraction < 1.0 && elapsed > 0.0
      ? ", about " + FormatSeconds(elapsed * (1.0 - fraction) / fraction) + " left"
      : "";
    if (this->Terminal)
    {
      const double sinceShown = std::chrono::duration<double>(now - this->Shown).count();
      if (percent == this->LastPercent && sinceShown < 0.5)
      {
        return;
      }
      this->Shown = now;
      std::string line = this->Label + ": " + std::to_string(percent) + " %" + left;
      const std::size_t width = line.size();
      line.resize(std::max(width, this->Width), ' '); // over the end of a longer line
      this->Width = width;
      this->Out << '\r' << line << std::flush;
      this->LastPercent = percent;
      return;
    }
    const int step = percent / 10;
    if (step > this->LastStep && percent > 0)
    {
      this->LastStep = step;
      this->Out << this->Label << ": " << 10 * step << " % after " << FormatSeconds(elapsed)
                << (step < 10 ? left : "") << std::endl;
    }
  }

  void Erase()
  {
    if (this->Terminal && this->Width > 0)
    {
      this->Out << '\r' << std::string(this->Width, ' ') << '\r' << std::flush;
      this->Width = 0;
    }
  }

  vtkObject* Source;
  unsigned long Tag = 0;
  std::string Label;
  std::ostream& Out;
  bool Terminal;
  bool Started = false;
  Clock::time_point Start, Shown;
  int LastPercent = -1;
  int LastStep = 0;
  std::size_t Width = 0;
};

/**
 * Progress of GPU frames, from vtkCausticsTimings' ProgressEvent (the source given
 * here is the pass's timings): nothing while a frame is under ShowAfter seconds;
 * after that, on a terminal one rewritten line (frame, the stage just done, the
 * time so far, and once a frame has finished the percentage and the time left),
 * otherwise one line per stage. Call NextFrame() before each frame.
 */
class FrameProgress
{
public:
  FrameProgress(
    vtkCausticsTimings* timings, std::string label, int frames, std::ostream& out = std::cout)
    : Source(timings)
    , Label(std::move(label))
    , Frames(frames)
    , Out(out)
    , Terminal(&out == &std::cout ? isatty(STDOUT_FILENO) != 0 : isatty(STDERR_FILENO) != 0)
  {
    this->Tag = timings->AddObserver(vtkCommand::ProgressEvent, this, &FrameProgress::OnProgress);
  }
  ~FrameProgress()
  {
    this->Source->RemoveObserver(this->Tag);
    this->Erase();
  }
  FrameProgress(const FrameProgress&) = delete;
  FrameProgress& operator=(const FrameProgress&) = delete;

  void NextFrame()
  {
    ++this->Frame;
    this->Start = Clock::now();
  }
  /** Seconds a frame runs before its progress shows (default 2). */
  void SetShowAfter(double seconds) { this->ShowAfter = seconds; }
  void SetTerminal(bool terminal) { this->Terminal = terminal; }

private:
  using Clock = std::chrono::steady_clock;

  void OnProgress(vtkObject*, unsigned long, void* data)
  {
    const double elapsed = std::chrono::duration<double>(Clock::now() - this->Start).count();
    if (elapsed < this->ShowAfter)
    {
      return;
    }
    const double fraction = *static_cast<double*>(data);
    std::ostringstream line;
    line << this->Label << ": frame " << this->Frame << " of " << this->Frames;
    if (fraction >= 1.0)
    {
      line << " done after " << FormatSeconds(elapsed);
    }
    else
    {
      line << ", " << this->Source->GetProgressStage() << " done after " << FormatSeconds(elapsed);
      if (fraction > 0.0) // known once a frame has finished
      {
        line << ", " << static_cast<int>(100.0 * fraction) << " %, about "
             << FormatSeconds(elapsed * (1.0 - fraction) / fraction) << " left";
      }
    }
    if (this->Terminal)
    {
      std::string text = line.str();
      const std::size_t width = text.size();
      text.resize(std::max(width, this->Width), ' ');
      this->Width = width;
      this->Out << '\r' << text << std::flush;
      if (fraction >= 1.0)
      {
        this->Out << '\n';
        this->Width = 0;
      }
      return;
    }
    this->Out << line.str() << std::endl;
  }

  void Erase()
  {
    if (this->Terminal && this->Width > 0)
    {
      this->Out << '\r' << std::string(this->Width, ' ') << '\r' << std::flush;
      this->Width = 0;
    }
  }

  vtkCausticsTimings* Source;
  unsigned long Tag = 0;
  std::string Label;
  int Frames;
  int Frame = 0;
  std::ostream& Out;
  bool Terminal;
  double ShowAfter = 2.0;
  Clock::time_point Start = Clock::now();
  std::size_t Width = 0;
};

/** Whether a VTK error that the program's body did not turn into an exception fails it. */
enum class LoggedErrors
{
  Fail,    ///< the run fails (exit code 1) naming the first one
  Remember ///< the body takes them (TakeError) where it can tell what they broke
};

/**
 * The main() of a caustics program: installs a OneLineOutputWindow (VTK 9.1 also
 * logs every error through loguru on stderr, which is silenced: one line is
 * enough), runs `body`, and maps what it throws to one line "PROGRAM: error: ..."
 * and an exit code: UsageError 2, NoWindowError 3, anything else 1, naming the
 * first VTK error seen when there was one (usually the cause of what failed later).
 */
inline int RunMain(const char* program, LoggedErrors logged,
  const std::function<int(OneLineOutputWindow* messages)>& body)
{
  vtkNew<OneLineOutputWindow> messages;
  messages->Program = program;
  vtkOutputWindow::SetInstance(messages);
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
  try
  {
    const int status = body(messages);
    const std::string error = logged == LoggedErrors::Fail ? messages->TakeError() : "";
    if (!error.empty())
    {
      throw std::runtime_error(error);
    }
    return status;
  }
  catch (const UsageError& e)
  {
    std::cerr << program << ": error: " << e.what() << "\n";
    return 2;
  }
  catch (const NoWindowError& e)
  {
    std::cerr << program << ": error: " << e.what() << "\n";
    return 3;
  }
  catch (const std::exception& e)
  {
    const std::string cause = messages->TakeError();
    std::cerr << program
              << ": error: " << (cause.empty() || cause == e.what() ? std::string(e.what()) : cause)
              << "\n";
    return 1;
  }
}
}

#endif
