// The report document as a self-contained web page (figures/REPORT.html): inline CSS and script, no
// network; figures referenced relative to the page. A navigation panel of the studies and their
// thesis items, counts at the top that filter the checks, filters by verdict, kind, basis and thesis
// discrepancy, wide tables scrolling inside their box, figures as thumbnails that open full size,
// and thesis curve values drawn on our curves as inline SVG. Opening the page with "#selftest"
// exercises all of this in the browser and writes the outcome into <pre id="selftest"> (the CTest
// test report_page reads it with headless Chromium: tests/report/check_report_page.py).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>
#include <sstream>

#include "check/report_document.hpp"

namespace fem::check::report {
namespace {

std::string esc(const std::string& s) {
    std::string out;
    for (char c : s) {
        switch (c) {
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '&': out += "&amp;"; break;
            case '"': out += "&quot;"; break;
            default: out += c;
        }
    }
    return out;
}

// A paragraph's text with its Markdown `code` spans as <code>.
std::string inline_html(const std::string& s) {
    std::string out;
    bool code = false;
    const std::string escaped = esc(s);
    const bool paired = std::count(s.begin(), s.end(), '`') % 2 == 0;
    for (char c : escaped) {
        if (c == '`' && paired) {
            out += code ? "</code>" : "<code>";
            code = !code;
        } else {
            out += c;
        }
    }
    return out;
}

std::string slug(const std::string& s) {
    std::string out;
    for (char c : s) {
        const bool keep = std::isalnum(static_cast<unsigned char>(c));
        if (keep) out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        else if (!out.empty() && out.back() != '-') out += '-';
    }
    while (!out.empty() && out.back() == '-') out.pop_back();
    return out.empty() ? "section" : out;
}

std::string fmt(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.4g", v);
    return buf;
}

// CSS class of a verdict label cell: the label text is all a table row has.
std::string verdict_cell_css(const std::string& label) {
    if (label == "pass") return "pass";
    if (label == "not reproduced") return "miss";
    if (label == "shown") return "shown";
    if (label.rfind("not run", 0) == 0) return "notrun";
    if (label.rfind("FAIL", 0) == 0) return "fail";
    return "";
}

const char* kStyle = R"css(
*{box-sizing:border-box}
body{margin:0;font-family:system-ui,sans-serif;color:#1d2330;background:#f6f7f9;font-size:15px;line-height:1.45}
#nav{position:fixed;top:0;left:0;bottom:0;width:270px;overflow-y:auto;background:#20283a;color:#dfe4ee;padding:12px 10px 40px;font-size:13px}
#nav a{color:#dfe4ee;text-decoration:none;display:block;padding:2px 6px;border-radius:4px}
#nav a:hover{background:#34405a}
#nav ul{list-style:none;margin:0;padding:0}
#nav ul ul{padding-left:12px;margin-bottom:4px}
#nav li.study>a{font-weight:600;margin-top:6px}
#nav li[hidden]{display:none}
#nav .nav-title{font-weight:700;font-size:15px;margin:2px 6px 8px}
main{margin-left:270px;padding:0 28px 60px;max-width:1500px}
h1{margin:18px 0 6px}
h2{margin-top:36px;border-bottom:2px solid #c9cfdb;padding-bottom:4px}
h3{margin-top:26px}
section[hidden]{display:none}
.badges{display:flex;flex-wrap:wrap;gap:6px;margin:8px 0;align-items:center}
.badges .lead{font-weight:600;margin-right:4px}
button.badge,.filters button{border:1px solid #9aa3b5;background:#fff;border-radius:14px;padding:3px 10px;cursor:pointer;font:inherit;font-size:13px}
button.badge b{margin-left:4px}
button.badge.pass{background:#dcf3dc}button.badge.fail{background:#f9c9c9}button.badge.miss{background:#fde7c4}
button.badge.shown{background:#e3e6f7}button.badge.notrun{background:#eeeeee}button.badge.disc{background:#eadcf7}
button.active{outline:3px solid #2f6fde}
.filters{position:sticky;top:0;z-index:5;background:#fff;border:1px solid #d3d8e2;border-radius:8px;padding:6px 10px;margin:10px 0;display:flex;flex-wrap:wrap;gap:8px;align-items:center;font-size:13px;box-shadow:0 2px 6px rgba(0,0,0,.06)}
.filters select{font:inherit;max-width:11em}
#filter-status{margin-left:auto;font-weight:600}
.scroll{overflow-x:auto;max-width:100%;margin:10px 0;border:1px solid #d3d8e2;border-radius:6px;background:#fff}
table{border-collapse:collapse;font-size:13px}
.scroll table{min-width:100%}
th,td{border-bottom:1px solid #e1e5ec;border-right:1px solid #eef0f4;padding:4px 7px;vertical-align:top;text-align:left}
th{background:#eef1f6;position:sticky;top:0}
tr[hidden]{display:none}
td.pass{background:#dcf3dc}td.fail{background:#f9c9c9;font-weight:600}td.miss{background:#fde7c4}td.shown{background:#e9ecf8}td.notrun{background:#eeeeee;color:#555}
td.id{white-space:nowrap;font-family:ui-monospace,monospace;font-size:12px}
td.note{min-width:26em;max-width:60em}
td.quantity{min-width:12em}
.gallery{display:flex;flex-wrap:wrap;gap:12px;margin:10px 0}
figure{margin:0}
figure.thumb{background:#fff;border:1px solid #d3d8e2;border-radius:6px;padding:6px;width:300px}
figure.thumb img{width:100%;height:200px;object-fit:contain;display:block;cursor:zoom-in}
figcaption{font-size:12px;color:#4a5366;margin-top:4px}
figure.plot{background:#fff;border:1px solid #d3d8e2;border-radius:6px;padding:8px;margin:10px 0;max-width:700px}
figure.plot svg{width:100%;height:auto;display:block}
svg .pass{fill:#2e9d44}svg .fail{fill:#d33}svg .miss{fill:#f29a1d}svg .shown{fill:#6a72c8}
#lightbox{position:fixed;inset:0;background:rgba(10,14,24,.88);z-index:20;display:flex;flex-direction:column;align-items:center;justify-content:center;cursor:zoom-out;padding:20px}
#lightbox[hidden]{display:none}
#lightbox img{max-width:96vw;max-height:88vh;background:#fff}
#lightbox div{color:#fff;margin-top:8px}
#selftest{display:none}
code{background:#e9ecf2;border-radius:3px;padding:0 3px;font-size:90%}
@media (max-width:900px){
 #nav{position:static;width:auto;max-height:38vh;padding-bottom:12px}
 main{margin-left:0;padding:0 10px 40px}
 figure.thumb{width:100%}
 td.note{min-width:18em}
}
)css";

const char* kScript = R"js(
(function(){
'use strict';
const rows=[...document.querySelectorAll('table.checks tr[data-verdict]')];
const keys=['verdict','kind','basis','disc'];
const F={verdict:'',kind:'',basis:'',disc:''};
function parse(s){const f={verdict:'',kind:'',basis:'',disc:''};(s||'').split(';').forEach(p=>{const i=p.indexOf('=');if(i>0&&p.slice(0,i) in f)f[p.slice(0,i)]=decodeURIComponent(p.slice(i+1));});return f;}
function text(f){return keys.filter(k=>f[k]).map(k=>k+'='+f[k]).join(';');}
function matches(d){return(!F.verdict||d.verdict===F.verdict)&&(!F.kind||d.kind===F.kind)&&(!F.basis||d.basis===F.basis)&&(!F.disc||d.disc==='1');}
function apply(f){
  Object.assign(F,f);
  let n=0;
  for(const r of rows){const ok=matches(r.dataset);r.hidden=!ok;if(ok)n++;}
  const active=text(F)!=='';
  const visibleRow='table.checks tr[data-verdict]:not([hidden])';
  document.querySelectorAll('section.s3').forEach(s=>{s.hidden=active&&!s.querySelector(visibleRow);});
  document.querySelectorAll('section.s2').forEach(s=>{s.hidden=active&&!s.querySelector(visibleRow);});
  document.querySelectorAll('#nav a[href^="#"]').forEach(a=>{const t=document.getElementById(a.getAttribute('href').slice(1));a.parentElement.hidden=!!(t&&t.closest('section[hidden]'));});
  const st=document.getElementById('filter-status');
  st.textContent=active?n+' of '+rows.length+' checks match':rows.length+' checks';
  st.dataset.visible=n;st.dataset.filter=text(F);
  keys.forEach(k=>{const e=document.getElementById('f-'+k);if(!e)return;if(e.type==='checkbox')e.checked=F[k]==='1';else e.value=F[k];});
  document.querySelectorAll('button[data-filter]').forEach(b=>b.classList.toggle('active',active&&b.dataset.filter===text(F)));
  return n;
}
function set(f){const n=apply(f);history.replaceState(null,'',text(F)?'#filter='+text(F):location.pathname);return n;}
document.querySelectorAll('button[data-filter]').forEach(b=>b.addEventListener('click',()=>set(parse(b.dataset.filter))));
keys.forEach(k=>{const e=document.getElementById('f-'+k);if(e)e.addEventListener('change',()=>{const f=Object.assign({},F);f[k]=e.type==='checkbox'?(e.checked?'1':''):e.value;set(f);});});
// Figures: thumbnails open full size over the page; a click or Escape closes.
const box=document.getElementById('lightbox'),boxImg=box.querySelector('img'),boxCap=box.querySelector('div');
document.querySelectorAll('a.thumb').forEach(a=>a.addEventListener('click',ev=>{ev.preventDefault();boxImg.src=a.getAttribute('href');boxCap.textContent=a.dataset.caption||'';box.hidden=false;}));
box.addEventListener('click',()=>{box.hidden=true;});
document.addEventListener('keydown',ev=>{if(ev.key==='Escape')box.hidden=true;});
if(location.hash.startsWith('#filter='))apply(parse(location.hash.slice(8)));else apply({});

// #selftest: what a test cannot see from outside the browser, written into <pre id="selftest"> once
// the page and its images have loaded (synchronously: headless Chromium dumps the DOM right after).
function selftest(){
  const out={images:0,broken_images:[],anchors:0,broken_anchors:[],files:[],filters:[],lightbox:{},plots:document.querySelectorAll('svg.plot').length,plot_points:document.querySelectorAll('svg.plot circle.point').length,checks:rows.length};
  for(const img of document.images){if(img.closest('#lightbox'))continue;out.images++;if(!(img.complete&&img.naturalWidth>0))out.broken_images.push(img.getAttribute('src'));}
  document.querySelectorAll('a[href]').forEach(a=>{const h=a.getAttribute('href');if(h.startsWith('#')){out.anchors++;if(!document.getElementById(decodeURIComponent(h.slice(1))))out.broken_anchors.push(h);}else out.files.push(h);});
  document.querySelectorAll('img[src]').forEach(i=>out.files.push(i.getAttribute('src')));
  const shown=()=>rows.filter(r=>r.getClientRects().length>0);
  const record=(name,filter,expected)=>{const matched=apply(parse(filter));const vis=shown();
    out.filters.push({name,filter,expected,matched,rendered:vis.length,ids:vis.map(r=>r.dataset.id),status:document.getElementById('filter-status').dataset.visible,
      hidden_sections:document.querySelectorAll('section[hidden]').length});};
  document.querySelectorAll('button[data-filter]').forEach(b=>{b.click();record(b.textContent.trim(),b.dataset.filter,b.dataset.count===undefined?null:+b.dataset.count);});
  ['kind','basis','verdict'].forEach(k=>{const e=document.getElementById('f-'+k);for(const o of e.options){if(!o.value)continue;e.value=o.value;e.dispatchEvent(new Event('change'));record(k+' '+o.value,k+'='+o.value,null);}});
  set({verdict:'',kind:'',basis:'',disc:''});
  out.after_reset=shown().length;
  const a=document.querySelector('a.thumb');
  if(a){a.click();out.lightbox.opened=getComputedStyle(box).display!=='none';out.lightbox.src=boxImg.getAttribute('src');
    out.lightbox.thumb=a.getAttribute('href');box.click();out.lightbox.closed=getComputedStyle(box).display==='none';}
  document.getElementById('selftest').textContent=JSON.stringify(out);
}
// "#selftest;filter=..." leaves the page filtered afterwards (for a screenshot taken in the same run).
function run(){try{const then=location.hash.split(';filter=')[1];selftest();if(then)set(parse(then.replace(/,/g,';')));}
  catch(e){document.getElementById('selftest').textContent=JSON.stringify({error:String(e&&e.stack||e)});}}
if(location.hash.startsWith('#selftest'))(document.readyState==='complete'?run():addEventListener('load',run));
})();
)js";

struct Anchor {
    int level;
    std::string id, nav;
};

// Anchors of the level-2 and level-3 headings, unique in the page (an item's anchor is prefixed by
// its study's, since "Solver runs" or "Table 2-5" can recur).
std::vector<Anchor> anchors(const std::vector<Block>& doc) {
    std::vector<Anchor> out;
    std::set<std::string> used;
    std::string parent;
    for (const auto& b : doc) {
        if (b.kind != Block::Heading || b.level < 2 || b.level > 3) continue;
        std::string base = b.level == 2 ? slug(b.nav.empty() ? b.text : b.nav) : parent + "--" + slug(b.text);
        std::string id = base;
        for (int k = 2; !used.insert(id).second; ++k) id = base + "-" + std::to_string(k);
        if (b.level == 2) parent = id;
        out.push_back({b.level, id, b.nav.empty() ? b.text : b.nav});
    }
    return out;
}

// Distinct values of one row tag, in the order they first appear.
std::vector<std::string> tag_values(const std::vector<Block>& doc, std::string RowTags::*field) {
    std::vector<std::string> out;
    for (const auto& b : doc)
        for (const auto& t : b.tags)
            if (std::find(out.begin(), out.end(), t.*field) == out.end()) out.push_back(t.*field);
    return out;
}

std::string verdict_option(const std::string& css) {
    static const std::map<std::string, std::string> names = {
        {"pass", "pass"}, {"fail", "failed"}, {"miss", "not reproduced (known miss)"}, {"shown", "shown"},
        {"notrun", "not run (make all only)"}};
    const auto it = names.find(css);
    return it == names.end() ? css : it->second;
}

void write_filters(std::ostringstream& h, const std::vector<Block>& doc) {
    h << "<div class=\"filters\" id=\"filters\"><b>Filter the checks:</b>\n"
         "<button data-filter=\"verdict=fail\">Failed</button>"
         "<button data-filter=\"verdict=miss\">Known misses</button>"
         "<button data-filter=\"disc=1\">Thesis discrepancies</button>"
         "<button data-filter=\"kind=reproduction\">Reproductions</button>\n";
    auto select = [&](const std::string& key, const std::string& label, std::string RowTags::*field, bool verdict) {
        h << "<label>" << label << " <select id=\"f-" << key << "\"><option value=\"\">any</option>";
        for (const auto& v : tag_values(doc, field))
            h << "<option value=\"" << esc(v) << "\">" << esc(verdict ? verdict_option(v) : v) << "</option>";
        h << "</select></label>\n";
    };
    select("verdict", "verdict", &RowTags::verdict, true);
    select("kind", "kind", &RowTags::kind, false);
    select("basis", "basis", &RowTags::basis, false);
    h << "<label><input type=\"checkbox\" id=\"f-disc\"> thesis discrepancies only</label>\n"
         "<button data-filter=\"\">Show all</button><span id=\"filter-status\"></span></div>\n";
}

void write_table(std::ostringstream& h, const Block& b) {
    const bool checks = !b.tags.empty();
    h << "<div class=\"scroll\"><table" << (checks ? " class=\"checks\"" : "") << "><thead><tr>";
    for (const auto& c : b.header) h << "<th>" << esc(c) << "</th>";
    h << "</tr></thead><tbody>\n";
    const auto col = [&](const char* name) { return std::find(b.header.begin(), b.header.end(), name) - b.header.begin(); };
    const long verdict_col = col("verdict"), note_col = col("note"), id_col = col("check"), quantity_col = col("quantity");
    for (std::size_t r = 0; r < b.rows.size(); ++r) {
        const auto& row = b.rows[r];
        h << "<tr";
        if (checks) {
            const RowTags& t = b.tags[r];
            h << " data-verdict=\"" << esc(t.verdict) << "\" data-kind=\"" << esc(t.kind) << "\" data-basis=\""
              << esc(t.basis) << "\" data-disc=\"" << (t.discrepancy ? "1" : "0") << "\"";
            if (id_col < static_cast<long>(row.size())) h << " data-id=\"" << esc(row[id_col]) << "\"";
        }
        h << ">";
        for (std::size_t i = 0; i < row.size(); ++i) {
            const long c = static_cast<long>(i);
            std::string css = c == verdict_col ? verdict_cell_css(row[i])
                              : c == note_col   ? "note"
                              : c == id_col     ? "id"
                              : c == quantity_col ? "quantity"
                                                  : "";
            h << (css.empty() ? "<td>" : "<td class=\"" + css + "\">") << esc(row[i]) << "</td>";
        }
        h << "</tr>\n";
    }
    h << "</tbody></table></div>\n";
}

}  // namespace

std::string plot_svg(const report::Plot& plot) {
    const double W = 660, H = 380, left = 72, right = 18, top = 34, bottom = 52;
    // Ranges over our curve and every thesis value with its band.
    double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
    auto extend = [&](double x, double y) {
        if (!std::isfinite(x) || !std::isfinite(y)) return;
        x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
    };
    for (const auto& [x, y] : plot.curve) extend(x, y);
    for (const auto& p : plot.points) extend(p.x, p.low), extend(p.x, p.high), extend(p.x, p.thesis);
    if (!(x1 >= x0)) x0 = 0, x1 = 1, y0 = 0, y1 = 1;
    if (x1 == x0) x0 -= 0.5, x1 += 0.5;
    if (y1 == y0) y0 -= 0.5, y1 += 0.5;
    const double pad = 0.05 * (y1 - y0);
    y0 -= pad, y1 += pad;
    auto px = [&](double x) { return left + (x - x0) / (x1 - x0) * (W - left - right); };
    auto py = [&](double y) { return H - bottom - (y - y0) / (y1 - y0) * (H - top - bottom); };
    auto ticks = [](double a, double b) {
        const double raw = (b - a) / 6, mag = std::pow(10.0, std::floor(std::log10(raw)));
        const double step = mag * (raw / mag < 1.5 ? 1 : raw / mag < 3.5 ? 2 : raw / mag < 7.5 ? 5 : 10);
        std::vector<double> t;
        for (double v = std::ceil(a / step) * step; v <= b + 1e-9 * step; v += step) t.push_back(std::abs(v) < 1e-12 * step ? 0 : v);
        return t;
    };
    std::ostringstream s;
    s << "<svg class=\"plot\" viewBox=\"0 0 " << W << ' ' << H << "\" xmlns=\"http://www.w3.org/2000/svg\" role=\"img\">"
      << "<title>" << esc(plot.title) << "</title>"
      << "<rect x=\"" << left << "\" y=\"" << top << "\" width=\"" << W - left - right << "\" height=\"" << H - top - bottom
      << "\" fill=\"#fbfcfe\" stroke=\"#9aa3b5\"/>";
    s << "<g font-size=\"12\" fill=\"#333\">";
    for (double t : ticks(x0, x1))
        s << "<line x1=\"" << px(t) << "\" x2=\"" << px(t) << "\" y1=\"" << top << "\" y2=\"" << H - bottom
          << "\" stroke=\"#e4e7ee\"/><text x=\"" << px(t) << "\" y=\"" << H - bottom + 16 << "\" text-anchor=\"middle\">"
          << fmt(t) << "</text>";
    for (double t : ticks(y0, y1))
        s << "<line x1=\"" << left << "\" x2=\"" << W - right << "\" y1=\"" << py(t) << "\" y2=\"" << py(t)
          << "\" stroke=\"#e4e7ee\"/><text x=\"" << left - 6 << "\" y=\"" << py(t) + 4 << "\" text-anchor=\"end\">" << fmt(t)
          << "</text>";
    s << "<text x=\"" << (left + W - right) / 2 << "\" y=\"" << H - 12 << "\" text-anchor=\"middle\">" << esc(plot.x_label)
      << "</text><text transform=\"translate(16," << (top + H - bottom) / 2 << ") rotate(-90)\" text-anchor=\"middle\">"
      << esc(plot.y_label) << "</text></g>";
    // Our curve (thinned to at most ~1500 vertices).
    const std::size_t stride = std::max<std::size_t>(1, plot.curve.size() / 1500);
    s << "<polyline class=\"curve\" fill=\"none\" stroke=\"#2f6fde\" stroke-width=\"1.8\" points=\"";
    for (std::size_t i = 0; i < plot.curve.size(); i += stride)
        if (std::isfinite(plot.curve[i].first) && std::isfinite(plot.curve[i].second))
            s << fmt(px(plot.curve[i].first)) << ',' << fmt(py(plot.curve[i].second)) << ' ';
    s << "\"/>";
    // The thesis's values: a marker coloured by the verdict, a bar for the tolerance band.
    for (const auto& p : plot.points) {
        const double x = px(p.x);
        s << "<g><title>" << esc(p.id) << ": thesis " << fmt(p.thesis) << " at " << esc(plot.x_label) << " = " << fmt(p.x)
          << " (tolerance " << fmt(p.low) << " .. " << fmt(p.high) << "); our curve there "
          << (p.ours_on_curve ? fmt(*p.ours_on_curve) : std::string("-")) << "; ours " << esc(p.ours) << ": " << esc(p.verdict)
          << "</title><line x1=\"" << x << "\" x2=\"" << x << "\" y1=\"" << py(p.low) << "\" y2=\"" << py(p.high)
          << "\" stroke=\"#333\" stroke-width=\"1.5\"/>";
        for (double y : {p.low, p.high})
            s << "<line x1=\"" << x - 5 << "\" x2=\"" << x + 5 << "\" y1=\"" << py(y) << "\" y2=\"" << py(y) << "\" stroke=\"#333\"/>";
        s << "<circle class=\"point " << esc(p.css) << "\" cx=\"" << x << "\" cy=\"" << py(p.thesis)
          << "\" r=\"5.5\" stroke=\"#111\" stroke-width=\"1.2\"/></g>";
    }
    // Legend.
    s << "<g font-size=\"12\"><line x1=\"" << left << "\" x2=\"" << left + 26 << "\" y1=\"16\" y2=\"16\" stroke=\"#2f6fde\" "
      << "stroke-width=\"1.8\"/><text x=\"" << left + 32 << "\" y=\"20\">ours</text><circle cx=\"" << left + 92
      << "\" cy=\"16\" r=\"5\" fill=\"#fff\" stroke=\"#111\"/><text x=\"" << left + 102
      << "\" y=\"20\">thesis value, bar = tolerance, colour = verdict</text></g></svg>";
    return s.str();
}

std::string to_html(const std::vector<Block>& doc) {
    const auto anchor_list = anchors(doc);
    std::ostringstream h;
    std::string title = "Reproduction report";
    for (const auto& b : doc)
        if (b.kind == Block::Heading && b.level == 1) {
            title = b.text;
            break;
        }
    h << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n"
         "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<title>"
      << esc(title) << "</title>\n<style>" << kStyle << "</style></head><body>\n";

    // Navigation: the report's sections, each study with its thesis items.
    h << "<nav id=\"nav\"><div class=\"nav-title\">" << esc(title) << "</div><ul>\n";
    for (std::size_t i = 0; i < anchor_list.size(); ++i) {
        const auto& a = anchor_list[i];
        if (a.level == 3) continue;
        const bool has_items = i + 1 < anchor_list.size() && anchor_list[i + 1].level == 3;
        h << "<li" << (has_items ? " class=\"study\"" : "") << "><a href=\"#" << a.id << "\">" << esc(a.nav) << "</a>";
        if (has_items) {
            h << "<ul>";
            for (std::size_t j = i + 1; j < anchor_list.size() && anchor_list[j].level == 3; ++j)
                h << "<li><a href=\"#" << anchor_list[j].id << "\">" << esc(anchor_list[j].nav) << "</a></li>";
            h << "</ul>";
        }
        h << "</li>\n";
    }
    h << "</ul></nav>\n<main>\n";

    std::size_t next_anchor = 0;
    int open = 0;  // open section levels: 0, 2 or 3
    auto close_to = [&](int level) {
        while (open >= level && open > 0) {
            h << "</section>\n";
            open = open == 3 ? 2 : 0;
        }
    };
    bool filters_written = false, in_gallery = false;
    for (std::size_t i = 0; i < doc.size(); ++i) {
        const Block& b = doc[i];
        if (in_gallery && b.kind != Block::Image) {
            h << "</div>\n";
            in_gallery = false;
        }
        switch (b.kind) {
            case Block::Heading: {
                if (b.level == 1) {
                    h << "<h1>" << esc(b.text) << "</h1>\n";
                    break;
                }
                if (b.level > 3) {
                    h << "<h" << b.level << ">" << esc(b.text) << "</h" << b.level << ">\n";
                    break;
                }
                const Anchor& a = anchor_list[next_anchor++];
                close_to(b.level);
                // The filter bar sits above the first section, outside all of them, so that it stays
                // at the top of the window however far one scrolls.
                if (!filters_written) {
                    write_filters(h, doc);
                    filters_written = true;
                }
                h << "<section class=\"s" << b.level << "\" id=\"" << a.id << "\"><h" << b.level << ">"
                  << esc(b.text) << "</h" << b.level << ">\n";
                open = b.level;
                break;
            }
            case Block::Paragraph: h << "<p>" << inline_html(b.text) << "</p>\n"; break;
            case Block::Table: write_table(h, b); break;
            case Block::Image:
                if (!in_gallery) h << "<div class=\"gallery\">\n";
                in_gallery = true;
                h << "<figure class=\"thumb\"><a class=\"thumb\" href=\"" << esc(b.file) << "\" data-caption=\""
                  << esc(b.text + ": " + b.file) << "\"><img src=\"" << esc(b.file) << "\" alt=\"" << esc(b.text)
                  << "\"></a><figcaption>" << esc(b.text) << " (" << esc(b.file) << ")</figcaption></figure>\n";
                break;
            case Block::Plot:
                h << "<figure class=\"plot\">" << plot_svg(b.plot) << "<figcaption>Thesis values on our curve: "
                  << esc(b.plot.title) << ". Hover a point for the numbers.</figcaption></figure>\n";
                break;
            case Block::Badges:
                h << "<div class=\"badges\"><span class=\"lead\">" << esc(b.text) << "</span>";
                for (const auto& badge : b.badges)
                    h << "<button class=\"badge " << esc(badge.css) << "\" data-filter=\"" << esc(badge.filter)
                      << "\" data-count=\"" << badge.count << "\">" << esc(badge.label) << " <b>" << badge.count << "</b></button>";
                h << "</div>\n";
                break;
        }
    }
    if (in_gallery) h << "</div>\n";
    close_to(2);
    if (!filters_written) write_filters(h, doc);
    h << "</main>\n<div id=\"lightbox\" hidden><img alt=\"full-size figure\"><div></div></div>\n"
         "<pre id=\"selftest\"></pre>\n<script>"
      << kScript << "</script>\n</body></html>\n";
    return h.str();
}

}  // namespace fem::check::report
