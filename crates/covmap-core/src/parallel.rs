//! Independent work on rayon's pool (feature `parallel`) or one piece after
//! the other, with the same results either way.

/// `f` of every item, the results in the items' order. With the feature
/// `parallel` the items are spread over rayon's pool; the order of the
/// results, and so anything computed from them, does not depend on how they
/// were scheduled.
pub fn map<T: Send, R: Send>(items: Vec<T>, f: impl Fn(T) -> R + Sync + Send) -> Vec<R> {
    #[cfg(feature = "parallel")]
    {
        use rayon::prelude::*;
        items.into_par_iter().map(f).collect()
    }
    #[cfg(not(feature = "parallel"))]
    items.into_iter().map(f).collect()
}

#[cfg(test)]
mod tests {
    /// The results come back in the items' order, however many there are.
    #[test]
    fn results_in_the_items_order() {
        for n in [0, 1, 7, 1000] {
            let items: Vec<u64> = (0..n).collect();
            let squares = super::map(items, |i| i * i);
            assert_eq!(squares, (0..n).map(|i| i * i).collect::<Vec<_>>());
        }
    }
}
