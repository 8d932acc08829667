//! A terminal's text as a PNG, for the README's screenshots: reads standard input and draws
//! it in a monospaced font (the TrueType file given as the first argument) into the PNG
//! given as the second. `scripts/screenshots.sh` uses it.

use ab_glyph::{point, Font, FontVec, PxScale, ScaleFont};
use plotters::prelude::*;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let (font, out) = match (args.get(1), args.get(2)) {
        (Some(f), Some(o)) => (f, o),
        _ => {
            eprintln!("usage: text_png FONT.ttf OUT.png < text");
            std::process::exit(2);
        }
    };
    let Ok(font) = FontVec::try_from_vec(std::fs::read(font).unwrap_or_default()) else {
        eprintln!("{font}: not a TrueType font");
        std::process::exit(2);
    };
    let mut text = String::new();
    std::io::Read::read_to_string(&mut std::io::stdin(), &mut text).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    let scaled = font.as_scaled(PxScale::from(16.0));
    let advance = scaled.h_advance(font.glyph_id('0'));
    let line_h = (scaled.height() + scaled.line_gap()).ceil();
    let columns = lines.iter().map(|l| l.chars().count()).max().unwrap_or(1);
    let (width, height) = (
        (columns as f32 * advance).ceil() as u32 + 32,
        (lines.len() as f32 * line_h).ceil() as u32 + 32,
    );
    let background = (250.0, 250.0, 248.0);
    let ink = (30.0, 30.0, 30.0);
    let root = BitMapBackend::new(out, (width, height)).into_drawing_area();
    root.fill(&RGBColor(250, 250, 248)).unwrap();
    for (i, line) in lines.iter().enumerate() {
        // every glyph on the line's baseline, one advance apart
        let baseline = 16.0 + scaled.ascent() + i as f32 * line_h;
        for (k, c) in line.chars().enumerate() {
            let glyph = font
                .glyph_id(c)
                .with_scale_and_position(16.0, point(16.0 + k as f32 * advance, baseline));
            let Some(outline) = font.outline_glyph(glyph) else {
                continue;
            };
            let b = outline.px_bounds();
            outline.draw(|x, y, coverage| {
                let mix = |bg: f32, fg: f32| (bg + (fg - bg) * coverage).round() as u8;
                let colour = RGBColor(
                    mix(background.0, ink.0),
                    mix(background.1, ink.1),
                    mix(background.2, ink.2),
                );
                let _ = root.draw_pixel(
                    (b.min.x as i32 + x as i32, b.min.y as i32 + y as i32),
                    &colour,
                );
            });
        }
    }
    root.present().unwrap();
}
