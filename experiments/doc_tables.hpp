// The measured tables of docs/experiments.md, kept equal to the commands that produce them.
//
// A command writes each of its tables as markdown to OUT/tables/NAME.md, first line a comment that
// says what each column is (`<!-- columns: exact | timed within 95% interval | host -->`):
//   exact   deterministic: the documented cell must equal the measured one, character for character;
//   timed within H   a median: the documented number must lie inside the measured row's interval,
//                    the cell of column H ("lo .. hi");
//   host    depends on the host and is not compared (an interval, a median without one, the host).
// The doc embeds a table between two marker lines (HTML comments, invisible on GitHub):
//   <!-- table: NAME from: rastercmp ARGS -->
//   | ... |
//   <!-- end table: NAME -->
// In ARGS, `{ARGS2}` stands for the output folder of `rastercmp ARGS2` (chart summary reads other
// runs' JSON). `rastercmp docs update|check DOC` (app/cmd_docs.cpp) runs each distinct command once
// with --out in a temporary folder, then rewrites the tables in place or compares them.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace rastercmp::experiments {

enum class ColumnKind { Exact, Timed, Host };

struct ColumnSpec {
  ColumnKind kind = ColumnKind::Exact;
  std::string interval_column;  // Timed: the header of the column holding the row's interval
};

struct MarkdownTable {
  std::vector<std::string> header;
  std::vector<ColumnSpec> columns;  // one per header cell; empty for a table read from the doc
  std::vector<std::vector<std::string>> rows;
};

// The table's lines (header, separator, rows), each ending in '\n'.
std::string render_markdown(const MarkdownTable& table);
// OUT/tables/NAME.md: the columns comment, then the table. Written atomically.
std::string table_file_text(const MarkdownTable& table);
void write_markdown_table(const std::string& out_dir, const std::string& name, const MarkdownTable& table);
// Reads OUT/tables/NAME.md back (with its columns). Throws UsageError naming the file and line.
MarkdownTable read_table_file(const std::string& path);
MarkdownTable parse_table_file(const std::string& text, const std::string& file);

// A table in a document, between its two markers (1-based line numbers of the marker lines).
struct DocMarker {
  std::string name;
  std::string command;  // as written after `from:`
  size_t begin_line = 0, end_line = 0;
  std::string indent;   // the begin marker's leading blanks, kept on every table line
};

// Every marker pair of the document; UsageError "FILE:LINE: ..." for a malformed or unpaired marker.
std::vector<DocMarker> parse_doc_markers(const std::string& text, const std::string& file);
// The documented table between a marker pair (no column kinds). UsageError "FILE:LINE: ..." when
// the lines there are not one markdown table.
MarkdownTable documented_table(const std::string& text, const DocMarker& marker, const std::string& file);

// A command line of a marker: its arguments (after `rastercmp`), where a `{...}` argument names a
// command whose output folder goes in its place.
struct DocCommand {
  std::string key;                  // the normalized command line: what deduplicates runs
  std::vector<std::string> args;    // without `rastercmp`; a dependency argument is empty
  std::vector<size_t> dependencies; // per argument: index into the command list + 1, or 0
};
// Adds `command` (and the commands in its braces, first) to `commands` unless already there;
// returns its index. UsageError naming FILE:LINE when it does not start with `rastercmp` or a
// brace is unbalanced.
size_t add_doc_command(std::vector<DocCommand>& commands, const std::string& command, const std::string& where);

struct CellDrift {
  std::string table, row, column, documented, measured;
  bool timed = false;
};
// The documented table against the measured one, by the measured table's column kinds.
std::vector<CellDrift> compare_tables(const std::string& name, const MarkdownTable& documented,
                                      const MarkdownTable& measured);

// The document with each marker's table replaced by tables.at(marker.name); every byte outside
// the marker pairs (the marker lines included) is kept. UsageError for a name missing from `tables`.
std::string rewrite_doc(const std::string& text, const std::vector<DocMarker>& markers,
                        const std::map<std::string, MarkdownTable>& tables, const std::string& file);

// Reads OUT_DIR/tables/NAME.md; UsageError naming the marker's FILE:LINE and the tables the
// command did write when there is no such table.
MarkdownTable measured_table(const std::string& out_dir, const DocMarker& marker, const std::string& file);

}  // namespace rastercmp::experiments
