mod fig1;
mod gain;
mod properties;
