mod fig1;
mod properties;
