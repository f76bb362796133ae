//! The robot as read: the description's table (DH rows or URDF joints), the chain of
//! elementary transforms the engine works on, the parameters, and every snapped value
//! with the error bound it implies.

use kinegen_core::chain::bound;
use kinegen_core::emit::mathml::escape;
use kinegen_core::Chain;

use super::html::{self, inline_code, Section};

/// The section.
pub fn section(chain: &Chain) -> Section {
    let mut body = String::new();
    body.push_str(&description(&chain.summary));
    if !chain.params.is_empty() {
        let rows: Vec<Vec<String>> = chain
            .params
            .iter()
            .map(|p| vec![escape(&p.name), escape(&p.value.to_string())])
            .collect();
        body.push_str("<h3>Parameters</h3>\n");
        body.push_str(&html::table(&["name", "value"], &rows));
    }
    body.push_str(
        "<h3>Chain</h3>\n<p>Elementary transforms, base to tip, as the engine reads them \
         (q<sub>i</sub> is joint i's variable):</p>\n<pre>",
    );
    body.push_str(&escape(&chain.to_string()));
    body.push_str("</pre>\n<h3>Snapped values</h3>\n");
    if chain.snaps.is_empty() {
        body.push_str(&html::p("None: the chain is the description as written."));
    } else {
        let rows: Vec<Vec<String>> = chain
            .snaps
            .iter()
            .map(|s| {
                vec![
                    format!("<code>{}</code>", escape(&s.entry)),
                    format!("<code>{}</code>", escape(&s.written)),
                    format!("<code>{}</code>", escape(&s.used)),
                    format!("{:.1e}", s.delta),
                    escape(&bound(s.position_bound)),
                    format!("{:.1e}", s.orientation_bound),
                ]
            })
            .collect();
        body.push_str(&html::table(
            &[
                "entry",
                "written",
                "used",
                "δ",
                "tool position ≤ (m)",
                "tool orientation ≤ (rad)",
            ],
            &rows,
        ));
        let (p, o) = chain.snap_bounds();
        body.push_str(&html::p(&format!(
            "Together, to first order: the tool within {} m and {:.1e} rad of the description read literally.",
            bound(p),
            o
        )));
    }
    Section {
        id: "robot",
        title: "The robot as read".into(),
        body,
    }
}

/// The description's markdown lines: `|` rows as a table, other lines as paragraphs.
fn description(lines: &[String]) -> String {
    let mut s = String::new();
    let mut rows: Vec<Vec<String>> = Vec::new();
    let flush = |rows: &mut Vec<Vec<String>>, s: &mut String| {
        if rows.is_empty() {
            return;
        }
        s.push_str("<table>\n");
        for (i, r) in rows.iter().enumerate() {
            let tag = if i == 0 { "th" } else { "td" };
            s.push_str("<tr>");
            for c in r {
                s.push_str(&format!("<{tag}>{}</{tag}>", inline_code(c)));
            }
            s.push_str("</tr>\n");
        }
        s.push_str("</table>\n");
        rows.clear();
    };
    for line in lines {
        let t = line.trim();
        if t.starts_with('|') {
            let cells: Vec<String> = t
                .trim_matches('|')
                .split('|')
                .map(|c| c.trim().to_string())
                .collect();
            // The markdown separator row `|---|---|`.
            if cells
                .iter()
                .all(|c| !c.is_empty() && c.chars().all(|ch| "-: ".contains(ch)))
            {
                continue;
            }
            rows.push(cells);
        } else {
            flush(&mut rows, &mut s);
            if !t.is_empty() {
                s.push_str(&format!("<p>{}</p>\n", inline_code(t)));
            }
        }
    }
    flush(&mut rows, &mut s);
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn markdown_tables_become_tables() {
        let lines: Vec<String> = [
            "Joints `a` & b",
            "",
            "| q | a |",
            "|---|---|",
            "| q1 | <0.5 |",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect();
        assert_eq!(
            description(&lines),
            "<p>Joints <code>a</code> &amp; b</p>\n<table>\n<tr><th>q</th><th>a</th></tr>\n\
             <tr><td>q1</td><td>&lt;0.5</td></tr>\n</table>\n"
        );
    }
}
