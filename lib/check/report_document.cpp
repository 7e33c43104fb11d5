// The report document as Markdown (figures/REPORT.md), and Markdown files read back as blocks.
#include <sstream>

#include "check/report_document.hpp"

namespace fem::check::report {
namespace {

std::string md_cell(const std::string& s) {
    std::string out;
    for (char c : s) {
        if (c == '|') out += "\\|";
        else if (c == '\n') out += ' ';
        else out += c;
    }
    return out;
}

void md_table(std::ostringstream& md, const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows) {
    md << '|';
    for (const auto& h : header) md << ' ' << md_cell(h) << " |";
    md << "\n|";
    for (std::size_t i = 0; i < header.size(); ++i) md << "---|";
    md << '\n';
    for (const auto& row : rows) {
        md << '|';
        for (const auto& c : row) md << ' ' << md_cell(c) << " |";
        md << '\n';
    }
    md << '\n';
}

// The cells of one Markdown table line ("| a | b \| c |"), unescaped.
std::vector<std::string> split_row(const std::string& line) {
    std::vector<std::string> cells;
    std::string cell;
    for (std::size_t i = line.find('|') + 1; i < line.size(); ++i) {
        if (line[i] == '\\' && i + 1 < line.size() && line[i + 1] == '|') {
            cell += '|';
            ++i;
        } else if (line[i] == '|') {
            cells.push_back(cell);
            cell.clear();
        } else {
            cell += line[i];
        }
    }
    for (auto& c : cells) {
        const auto a = c.find_first_not_of(' '), b = c.find_last_not_of(' ');
        c = a == std::string::npos ? "" : c.substr(a, b - a + 1);
    }
    return cells;
}

}  // namespace

std::string number(double v) {
    std::ostringstream s;
    s.precision(6);
    s << v;
    return s.str();
}

std::string to_markdown(const std::vector<Block>& doc) {
    std::ostringstream md;
    for (const auto& b : doc) {
        switch (b.kind) {
            case Block::Heading: md << std::string(b.level, '#') << ' ' << b.text << "\n\n"; break;
            case Block::Paragraph: md << b.text << "\n\n"; break;
            case Block::Image: md << "![" << b.text << "](" << b.file << ")\n\n"; break;
            case Block::Table: md_table(md, b.header, b.rows); break;
            case Block::Badges: {
                std::string line;
                for (const auto& badge : b.badges)
                    line += (line.empty() ? "" : " · ") + badge.label + " **" + std::to_string(badge.count) + "**";
                md << b.text << ' ' << line << "\n\n";
                break;
            }
            case Block::Plot: {
                md << "Thesis values on our curve (" << b.plot.title << "; drawn in REPORT.html):\n\n";
                std::vector<std::vector<std::string>> rows;
                for (const auto& p : b.plot.points)
                    rows.push_back({p.id, number(p.x), number(p.thesis), number(p.low) + " .. " + number(p.high),
                                    p.ours_on_curve ? number(*p.ours_on_curve) : "(outside our curve)", p.ours, p.verdict});
                md_table(md, {"check", b.plot.x_label, "thesis", "tolerance band", "our curve there", "ours (the check)", "verdict"},
                         rows);
                break;
            }
        }
    }
    return md.str();
}

std::vector<Block> markdown_blocks(const std::string& text) {
    std::vector<Block> blocks;
    std::istringstream in(text);
    std::string line, paragraph;
    Block* table = nullptr;
    auto flush_paragraph = [&]() {
        if (!paragraph.empty()) blocks.push_back({Block::Paragraph, 0, paragraph});
        paragraph.clear();
    };
    while (std::getline(in, line)) {
        const auto first = line.find_first_not_of(" \t\r");
        if (first != std::string::npos && line[first] == '|') {
            flush_paragraph();
            auto cells = split_row(line);
            const bool separator = !cells.empty() && cells[0].find("---") != std::string::npos;
            if (!table) {
                blocks.push_back({Block::Table});
                table = &blocks.back();
                table->header = std::move(cells);
            } else if (!separator) {
                table->rows.push_back(std::move(cells));
            }
            continue;
        }
        table = nullptr;
        if (first == std::string::npos) {
            flush_paragraph();
            continue;
        }
        std::string words = line.substr(first);
        while (!words.empty() && words[0] == '#') words.erase(0, 1);  // a heading becomes a plain line
        const auto word_start = words.find_first_not_of(' ');
        if (word_start == std::string::npos) continue;
        if (!paragraph.empty()) paragraph += ' ';
        paragraph.append(words, word_start);
    }
    flush_paragraph();
    return blocks;
}

}  // namespace fem::check::report
