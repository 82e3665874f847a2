//! Where labels go on an image of regions (the patches of a patch-id image): each on a pixel
//! of its region as far from the region's edges as can be, clear of the labels placed before.

use std::collections::VecDeque;

use super::text::PixelRect;

/// The id of pixels that belong to no region (the background of a patch-id image).
pub const NO_REGION: u32 = u32::MAX;

/// A label to place: the region it names and the size of its box.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LabelRequest {
    pub region: u32,
    pub size: (u32, u32),
}

/// A placed label: the region's pixel it stands for and its box, inside the image.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Placement {
    pub region: u32,
    /// A pixel of the region, inside `rect`.
    pub anchor: (u32, u32),
    pub rect: PixelRect,
}

/// Each region's distance to its edge: 0 on a region's pixels that touch (4-neighbours) another
/// region, the background or the image's border, and from there the number of 8-neighbour
/// steps inside the region (the chessboard distance); 0 on the background.
#[must_use]
pub fn distance_to_edges(ids: &[u32], width: u32, height: u32) -> Vec<u32> {
    let (w, h) = (width as usize, height as usize);
    let mut distance = vec![u32::MAX; ids.len()];
    let mut queue = VecDeque::new();
    for y in 0..h {
        for x in 0..w {
            let i = y * w + x;
            if ids[i] == NO_REGION {
                distance[i] = 0;
                continue;
            }
            let on_border = x == 0 || y == 0 || x + 1 == w || y + 1 == h;
            let touches = on_border
                || ids[i - 1] != ids[i]
                || ids[i + 1] != ids[i]
                || ids[i - w] != ids[i]
                || ids[i + w] != ids[i];
            if touches {
                distance[i] = 0;
                queue.push_back(i);
            }
        }
    }
    while let Some(i) = queue.pop_front() {
        let (x, y) = ((i % w) as i64, (i / w) as i64);
        for (dx, dy) in [
            (-1, -1),
            (0, -1),
            (1, -1),
            (-1, 0),
            (1, 0),
            (-1, 1),
            (0, 1),
            (1, 1),
        ] {
            let (nx, ny) = (x + dx, y + dy);
            if nx < 0 || ny < 0 || nx >= w as i64 || ny >= h as i64 {
                continue;
            }
            let n = ny as usize * w + nx as usize;
            if ids[n] == ids[i] && distance[n] == u32::MAX {
                distance[n] = distance[i] + 1;
                queue.push_back(n);
            }
        }
    }
    distance
}

/// Places each request's box on the image, largest region first.
///
/// A region's candidate anchors are its pixels from the farthest from its edges
/// ([`distance_to_edges`]) to the nearest, ties in reading order; a box is centred on its anchor
/// and moved the least that keeps it inside the image ([`PixelRect::centred_inside`]), which
/// leaves the anchor inside it. A label takes the first candidate whose box overlaps no label
/// placed before it nor any of `occupied`, or, when every one does, the first. A region with
/// no pixel gets no label. The placements come in the order of `requests`.
#[must_use]
pub fn place_labels(
    ids: &[u32],
    (width, height): (u32, u32),
    requests: &[LabelRequest],
    occupied: &[PixelRect],
) -> Vec<Placement> {
    let distance = distance_to_edges(ids, width, height);
    let mut pixels_of: Vec<Vec<u32>> = vec![Vec::new(); requests.len()];
    let request_of = |region: u32| requests.iter().position(|r| r.region == region);
    let mut index_of_region = std::collections::HashMap::new();
    for (i, &id) in ids.iter().enumerate() {
        if id == NO_REGION {
            continue;
        }
        let request = *index_of_region.entry(id).or_insert_with(|| request_of(id));
        if let Some(r) = request {
            pixels_of[r].push(i as u32);
        }
    }
    let mut order: Vec<usize> = (0..requests.len()).collect();
    order.sort_by_key(|&r| (std::cmp::Reverse(pixels_of[r].len()), r));
    let mut placed: Vec<Option<Placement>> = vec![None; requests.len()];
    let mut boxes: Vec<PixelRect> = occupied.to_vec();
    for r in order {
        let pixels = &mut pixels_of[r];
        if pixels.is_empty() {
            continue;
        }
        // Stable: equal distances stay in reading order.
        pixels.sort_by_key(|&i| std::cmp::Reverse(distance[i as usize]));
        let at = |i: u32| {
            let anchor = (i % width, i / width);
            let rect = PixelRect::centred_inside(
                requests[r].size,
                (i64::from(anchor.0), i64::from(anchor.1)),
                (width, height),
            );
            Placement {
                region: requests[r].region,
                anchor,
                rect,
            }
        };
        let chosen = pixels
            .iter()
            .map(|&i| at(i))
            .find(|p| boxes.iter().all(|b| !b.overlaps(&p.rect)))
            .unwrap_or_else(|| at(pixels[0]));
        boxes.push(chosen.rect);
        placed[r] = Some(chosen);
    }
    placed.into_iter().flatten().collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 12 × 6 image: region 0 on the left two thirds, region 1 on the right third.
    fn two_regions() -> Vec<u32> {
        (0..6)
            .flat_map(|_| (0..12).map(|x| if x < 8 { 0 } else { 1 }))
            .collect()
    }

    #[test]
    fn distance_grows_inward_from_region_edges() {
        let ids = two_regions();
        let d = distance_to_edges(&ids, 12, 6);
        let at = |x: usize, y: usize| d[y * 12 + x];
        // The image border and the line between the regions are edges.
        assert_eq!((at(0, 3), at(7, 3), at(8, 3), at(11, 0)), (0, 0, 0, 0));
        assert_eq!(at(1, 1), 1);
        assert_eq!(at(3, 2), 2);
        assert_eq!(at(9, 2), 1);
    }

    #[test]
    fn labels_sit_on_their_region_inside_the_image_and_apart() {
        let ids = two_regions();
        let requests = [
            LabelRequest {
                region: 1,
                size: (3, 2),
            },
            LabelRequest {
                region: 0,
                size: (4, 2),
            },
            LabelRequest {
                region: 7,
                size: (4, 2),
            },
        ];
        let placed = place_labels(&ids, (12, 6), &requests, &[]);
        // Region 7 has no pixel: no label.
        assert_eq!(placed.len(), 2);
        assert_eq!((placed[0].region, placed[1].region), (1, 0));
        for p in &placed {
            let (x, y) = p.anchor;
            assert_eq!(ids[(y * 12 + x) as usize], p.region);
            assert!(p.rect.contains(i64::from(x), i64::from(y)));
            assert!(p.rect.x >= 0 && p.rect.y >= 0);
            assert!(p.rect.x + i64::from(p.rect.width) <= 12);
            assert!(p.rect.y + i64::from(p.rect.height) <= 6);
        }
        assert!(!placed[0].rect.overlaps(&placed[1].rect));
        // The larger region is placed first, at its pixel farthest from its edges.
        assert_eq!(placed[1].anchor, (2, 2));
        // A box already there (a legend) moves it to the next farthest pixel clear of it.
        let legend = PixelRect {
            x: 0,
            y: 0,
            width: 4,
            height: 2,
        };
        let placed = place_labels(&ids, (12, 6), &requests[1..2], &[legend]);
        assert_eq!(placed[0].anchor, (2, 3));
        assert!(!placed[0].rect.overlaps(&legend));
    }

    #[test]
    fn a_label_with_no_free_room_still_goes_on_its_region() {
        // Two 2 × 4 regions side by side, each label as big as the image.
        let ids: Vec<u32> = (0..4)
            .flat_map(|_| (0..4).map(|x| if x < 2 { 3 } else { 4 }))
            .collect();
        let requests = [3, 4].map(|region| LabelRequest {
            region,
            size: (4, 4),
        });
        let placed = place_labels(&ids, (4, 4), &requests, &[]);
        assert_eq!(placed.len(), 2);
        assert_eq!(placed[0].rect, placed[1].rect);
        for p in &placed {
            assert_eq!(ids[(p.anchor.1 * 4 + p.anchor.0) as usize], p.region);
        }
    }
}
