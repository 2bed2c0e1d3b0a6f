mod exploration;
mod fig1;
mod gain;
mod logs;
mod properties;
